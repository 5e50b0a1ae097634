// ugv-pose's configuration keys (docs/pose.md lists each with its default and range).
#pragma once

#include <string>

#include "ugv/estimation/pose_estimator.hpp"
#include "ugv/runtime/config.hpp"
#include "ugv/runtime/stamp_gate.hpp"

namespace ugv::pose_daemon {

struct PoseConfig
{
    estimation::EstimatorConfig estimator;
    std::string gps_fix_channel = "GPS_FIX";
    std::string gps_velocity_channel = "GPS_VEL";
    std::string imu_channel = "IMU";
    std::string channel = "POSE";
    // Inputs stamped beyond these from the bus clock are refused (runtime/stamp_gate.hpp).
    int64_t max_stamp_ahead_us = 2'000'000;
    runtime::StampSkewLimits stamp_skew;  // max_stamp_skew_s, max_stamp_lag_s: the clock-disagreement flag
    int64_t max_stamp_age_us = 2'000'000;
};

// Reads every key (ConfigError on a bad one: the daemon exits 2 with `FILE: KEY: why`).
PoseConfig read_config(runtime::Config& cfg);

}  // namespace ugv::pose_daemon
