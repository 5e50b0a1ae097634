// ugv-nodscan configuration keys (docs/nodscan.md lists them all).
#pragma once

#include <cstdint>
#include <string>

#include "ugv/nodscan/scan_assembler.hpp"
#include "ugv/runtime/config.hpp"
#include "ugv/runtime/stamp_gate.hpp"

namespace ugv::nodscan_daemon {

struct NodscanConfig
{
    std::string scan_channel = "LMS_SCAN";
    std::string servo_channel = "SERVO_STATE";
    std::string channel = "POINTS";
    std::string sensor_id;  // only scans from this laser ("" = any)
    nodscan::AssemblerConfig assembler;
    int64_t max_wait_us = 100'000;    // how long a scan may wait for a bracketing servo sample
    int64_t servo_history_us = 2'000'000;
    std::size_t max_pending_scans = 8;
    // Inputs stamped further ahead of the bus clock are refused; older than servo_history_us
    // behind it, too (runtime/stamp_gate.hpp).
    int64_t max_stamp_ahead_us = 2'000'000;
    runtime::StampSkewLimits stamp_skew;  // max_stamp_skew_s, max_stamp_lag_s: the clock-disagreement flag
};

NodscanConfig read_config(runtime::Config& cfg);

}  // namespace ugv::nodscan_daemon
