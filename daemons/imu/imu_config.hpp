// ugv-imu's configuration keys (docs/imu.md lists them with types, defaults and ranges).
#pragma once

#include <string>

#include "ugv/microstrain_gx1/orientation.hpp"
#include "ugv/microstrain_gx1/session.hpp"
#include "ugv/runtime/config.hpp"

namespace ugv::imu_daemon {

struct ImuConfig
{
    std::string device = "/dev/ugv/imu";
    int baud = 38400;
    std::string channel = "IMU";
    bool publish_raw = false;
    std::string raw_channel = "RAW_IMU";
    double orientation_sigma_rad = 0;
    microstrain_gx1::SessionConfig session;
    Eigen::Matrix3d r_body_sensor = Eigen::Matrix3d::Identity();
    double declination_rad = 0;
};

// Reads every key (throws runtime::ConfigError on a bad one). Call before Daemon::start().
ImuConfig read_config(runtime::Config& cfg);

}  // namespace ugv::imu_daemon
