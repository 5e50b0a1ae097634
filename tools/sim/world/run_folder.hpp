// What ugv-sim world leaves in its run folder besides the device links: the truth height
// field (for ugv-eval), the vehicle's calibration as the daemons' config fragments (what a
// calibration of the real vehicle would give), the scenario it ran, and the ready marker.
#pragma once

#include <cstddef>
#include <string>

#include "ugv/simworld/world.hpp"

namespace ugv::sim::world {

// What the daemons are told (the scenario's configured mounts; `truth` = true: the true
// ones instead, for checking a calibration). TOML for ugv-nodscan: the [mount] table of
// scenario().lasers[laser]. For ugv-pose: gps_antenna_m, then the [datum] table. Each starts
// with its top-level keys and ends with its table, so it can be appended to a config that
// has only top-level keys. For ugv-imu: mount_rpy_deg, a top-level key only.
std::string nodscan_calibration(const simworld::Scenario& s, std::size_t laser, bool truth = false);
std::string pose_calibration(const simworld::Scenario& s, bool truth = false);
std::string imu_calibration(const simworld::Scenario& s, bool truth = false);
// TOML for ugv-servo: the laser's drive (node_id, counts_per_rev, gear_ratio), top-level
// keys only, so it goes before a config's tables.
std::string servo_calibration(const simworld::Scenario& s, std::size_t laser);

// Writes path atomically (a temporary file renamed into place); throws std::runtime_error.
void write_file(const std::string& path, const std::string& bytes);

// Writes truth.hf, scenario.toml, calibration/{nodscan,pose,imu}.toml into dir (per named
// laser calibration/nodscan-NAME.toml and calibration/servo-NAME.toml), and the true mounts
// in the same files under true-calibration/.
void write_run_folder(const std::string& dir, const simworld::World& world, const std::string& scenario_toml);

}  // namespace ugv::sim::world
