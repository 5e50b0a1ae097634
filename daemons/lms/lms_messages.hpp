// A session's StampedScan as the laser_scan_t published on LMS_SCAN.
#pragma once

#include <cstdint>
#include <string>

#include <ugv/laser_scan_t.hpp>

#include "ugv/sick_lms2xx/session.hpp"

namespace ugv::lms_daemon {

ugv::laser_scan_t to_message(const sick_lms2xx::StampedScan& s, const std::string& sensor_id, int64_t seq);

}  // namespace ugv::lms_daemon
