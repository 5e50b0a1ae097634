// ugv-calibrate antenna LOG: the GPS antenna's lever arm from GPS_VEL + IMU of a drive with
// turns (lib/calibrate antenna_fit.hpp). A thin adapter: reads the log, pairs each GPS
// velocity with the IMU around it, hands them to the fit, prints the estimate, its sigmas,
// what the drive could not determine, and a ready gps_antenna_m line for ugv-pose.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "ugv/calibrate/antenna_fit.hpp"

namespace ugv::calibrate_tool {

class AntennaCommand
{
public:
    explicit AntennaCommand(CLI::App& app);
    AntennaCommand(const AntennaCommand&) = delete;  // CLI11 holds references to the members
    AntennaCommand& operator=(const AntennaCommand&) = delete;
    bool chosen() const { return sub_->parsed(); }
    // 0 with an estimate; 2 when the log or the config cannot be read or cannot give one.
    int run() const;

private:
    CLI::App* sub_;
    std::string log_, pose_config_, gps_channel_ = "GPS_VEL", imu_channel_ = "IMU";
    calibrate::AntennaFitConfig fit_;
    bool json_ = false;
};

}  // namespace ugv::calibrate_tool
