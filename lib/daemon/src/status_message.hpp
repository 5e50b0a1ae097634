#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "ugv/daemon_status_t.hpp"

namespace ugv::daemon {

// Builds the daemon_status_t of one 1 Hz report.
ugv::daemon_status_t make_status_message(int64_t utime, int64_t seq, const std::string& name,
                                         const std::string& instance, int8_t state, const std::string& last_error,
                                         int64_t uptime_us,
                                         const std::vector<std::pair<std::string, int64_t>>& counters);

}  // namespace ugv::daemon
