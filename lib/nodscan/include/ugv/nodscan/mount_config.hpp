// The [mount] table of a nodscan configuration (docs/nodscan.md), read the same way by
// ugv-nodscan and by the tools that start from its mount (ugv-calibrate).
#pragma once

#include "ugv/nodscan/mount.hpp"
#include "ugv/runtime/config.hpp"

namespace ugv::nodscan {

// Reads tilt_axis_xyz_m, tilt_axis_rpy_deg, laser_xyz_m and laser_rpy_deg from `mount` (the
// [mount] section); throws runtime::ConfigError for a value out of its range.
MountGeometry read_mount(runtime::Config& mount);

}  // namespace ugv::nodscan
