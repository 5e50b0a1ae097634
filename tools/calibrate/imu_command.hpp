// ugv-calibrate imu LOG: the IMU's mounting from the IMU channel of a recording that stands
// still and then drives straight, speeding up and braking (lib/calibrate imu_mount_fit.hpp).
// A thin adapter: reads the log, hands the samples to the fit, prints the estimate, its
// sigmas, what the data could not determine, and a ready mount_rpy_deg line for ugv-imu.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "ugv/calibrate/imu_mount_fit.hpp"

namespace ugv::calibrate_tool {

class ImuCommand
{
public:
    explicit ImuCommand(CLI::App& app);
    ImuCommand(const ImuCommand&) = delete;  // CLI11 holds references to the members
    ImuCommand& operator=(const ImuCommand&) = delete;
    bool chosen() const { return sub_->parsed(); }
    // 0 with an estimate; 2 when the log or the config cannot be read or cannot give one.
    int run() const;

private:
    CLI::App* sub_;
    std::string log_, mount_config_, channel_ = "IMU";
    calibrate::ImuMountFitConfig fit_;
    bool json_ = false;
};

}  // namespace ugv::calibrate_tool
