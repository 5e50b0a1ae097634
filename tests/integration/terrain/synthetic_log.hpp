// A synthetic drive for the terrain daemon's tests and replay benchmark: flat ground with
// one box, a vehicle that drives straight for 3 s and then turns left while driving, POSE
// at 10 Hz and, per laser, POINTS.<name> (one nodding line of ground points per message;
// 25 Hz x 121 points by default), written as an LCM log.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace ugv::test {

struct SyntheticDrive
{
    double duration_s = 5.0;
    Eigen::Vector2d box_min{8.0, 0.8};  // m, ENU
    Eigen::Vector2d box_max{8.4, 1.2};
    double box_height_m = 0.5;
    double orientation_sigma_rad = 0.3 * M_PI / 180.0;
    int64_t start_utime = 1'700'000'000'000'000;
    double turn_rate_rad_s = 0.3;       // after the first 3 s
    std::vector<std::string> lasers = {"front"};  // channel POINTS.<name>; the lasers scan in turn
    int64_t cloud_period_us = 40'000;   // per laser
    int points_per_cloud = 121;         // spread over 12 m across the vehicle

    double height_at(double x, double y) const;
    // Vehicle (body origin) pose at t seconds from the start: x, y, yaw.
    Eigen::Vector3d pose_at(double t) const;
    // Every message in time order: channel, utime, encoded bytes.
    void events(const std::function<void(const std::string&, int64_t, const std::vector<uint8_t>&)>& out) const;
    void write_log(const std::string& path) const;
};

}  // namespace ugv::test
