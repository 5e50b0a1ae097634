// ugv-calibrate laser LOG: the nodding laser's mount from LMS_SCAN + SERVO_STATE of a log
// recorded over flat ground (lib/calibrate laser_mount_fit.hpp). A thin adapter: reads the
// log, gives each beam its tilt at its own time, hands the beams to the fit, prints the
// estimate, its sigmas, what the data could not determine, and a ready [mount] table.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "ugv/calibrate/laser_mount_fit.hpp"

namespace ugv::calibrate_tool {

class LaserCommand
{
public:
    explicit LaserCommand(CLI::App& app);
    LaserCommand(const LaserCommand&) = delete;  // CLI11 holds references to the members
    LaserCommand& operator=(const LaserCommand&) = delete;
    bool chosen() const { return sub_->parsed(); }
    // 0 with an estimate; 2 when the log or the config cannot be read or cannot give one.
    int run() const;

private:
    CLI::App* sub_;
    std::string log_, mount_config_, scan_channel_ = "LMS_SCAN", servo_channel_ = "SERVO_STATE", sensor_id_;
    calibrate::LaserFitConfig fit_;
    std::size_t max_beams_ = 400000;
    int blocks_ = 8;
    bool json_ = false;
};

}  // namespace ugv::calibrate_tool
