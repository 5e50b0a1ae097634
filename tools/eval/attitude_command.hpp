// ugv-eval attitude LOG: roll, pitch and yaw errors of the IMU's own attitude output and of
// the pose against SIM_TRUTH, standing, driving straight and turning (attitude_error.hpp).
// A thin adapter: reads the log, prints one JSON line per source and motion. --pose-log takes
// the pose from a second log instead (an `ugv-pose --replay` of the first).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace ugv::eval {

class AttitudeCommand
{
public:
    explicit AttitudeCommand(CLI::App& app);
    AttitudeCommand(const AttitudeCommand&) = delete;  // CLI11 holds references to the members
    AttitudeCommand& operator=(const AttitudeCommand&) = delete;
    bool chosen() const { return sub_->parsed(); }
    // 0 with results, 1 when the log has no truth or nothing to score, 2 when it cannot be read.
    int run() const;

private:
    CLI::App* sub_;
    std::string log_, pose_log_, imu_channel_ = "IMU", pose_channel_ = "POSE", truth_channel_ = "SIM_TRUTH";
    double turn_rate_dps_ = 1.0, standing_speed_mps_ = 0.1;
};

}  // namespace ugv::eval
