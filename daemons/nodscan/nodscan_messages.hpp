// laser_scan_t / point_cloud_t <-> the nodscan library's types.
#pragma once

#include <cstdint>
#include <string>

#include "ugv/laser_scan_t.hpp"
#include "ugv/nodscan/scan_assembler.hpp"
#include "ugv/point_cloud_t.hpp"

namespace ugv::nodscan_daemon {

// A view of the scan's ranges (valid while the message lives); n is bounded by the array.
// A sweep layout that is not one (see ScanView::set_sweeps) gives sweeps = 0.
nodscan::ScanView to_scan_view(const laser_scan_t& scan);
point_cloud_t to_message(const nodscan::PointCloud& cloud, const std::string& sensor_id, int64_t seq);

}  // namespace ugv::nodscan_daemon
