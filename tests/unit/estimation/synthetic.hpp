// Synthetic vehicle trajectories on flat ground with the GPS and IMU measurements a vehicle
// would produce along them, with seeded Gaussian noise of known size. Test support only.
#pragma once

#include <cstdint>
#include <functional>
#include <random>
#include <variant>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "ugv/estimation/inputs.hpp"
#include "ugv/estimation/local_frame.hpp"

namespace ugv::estimation::synthetic {

// Truth at time t (s from the start): the body follows its velocity (no sideslip), roll and
// pitch are zero.
struct Truth
{
    Eigen::Vector3d position = Eigen::Vector3d::Zero();      // m, ENU
    Eigen::Vector3d velocity = Eigen::Vector3d::Zero();      // m/s
    Eigen::Vector3d acceleration = Eigen::Vector3d::Zero();  // m/s^2
    double yaw = 0.0;       // rad, ENU
    double yaw_rate = 0.0;  // rad/s
    Eigen::Quaterniond attitude() const;
};
using Trajectory = std::function<Truth(double t)>;

// From rest, accelerating at accel_mps2 along heading_rad until speed_mps, then constant.
Trajectory straight(double heading_rad, double accel_mps2, double speed_mps);
// Counter-clockwise circle of radius_m about the origin at speed_mps.
Trajectory circle(double radius_m, double speed_mps);
// Lissajous figure eight x = a sin(wt), y = a/2 sin(2wt); period 2 pi / w.
Trajectory figure_eight(double a_m, double omega_rps);

struct Noise
{
    double gps_sigma_horizontal_m = 0.5;
    double gps_sigma_vertical_m = 1.0;
    double gps_velocity_sigma_mps = 0.05;
    double imu_orientation_sigma_rad = 0.01;
    double gyro_density = 0.005;   // rad/s/sqrt(Hz)
    double accel_density = 0.05;   // m/s^2/sqrt(Hz)
    double heading_offset_rad = 0.3;  // IMU yaw minus true yaw
    // A compass's deviation (hard iron): the IMU's yaw is off by a further
    // compass_deviation_rad x sin(true yaw), an error that changes with the heading.
    double compass_deviation_rad = 0.0;
    Eigen::Vector3d gyro_bias_rps = Eigen::Vector3d::Zero();  // constant, added to every rate
    // > 0: the IMU's orientation comes from an AHRS-like complementary filter (gyros plus a
    // pull toward the accelerometers' "down" with this time constant), so it takes the
    // vehicle's acceleration for tilt; its yaw is kept at true yaw + heading offset. 0: truth
    // plus white noise.
    double ahrs_time_constant_s = 0.0;
    double imu_hz = 50.0;
    double gps_hz = 5.0;
};

using Input = std::variant<ImuSample, GpsFix, GpsVelocity>;
int64_t utime_of(const Input& in);

struct Run
{
    std::vector<Input> inputs;  // in time order
    int64_t start_utime = 0;
};

// Measurements from t = 0 to duration_s; utime = start_utime + t.
Run simulate(const Trajectory& trajectory, const Noise& noise, const Datum& datum, double duration_s, uint32_t seed,
             int64_t start_utime = 1'700'000'000'000'000);

// The truth at a utime of a run.
Truth truth_at(const Trajectory& trajectory, const Run& run, int64_t utime);

}  // namespace ugv::estimation::synthetic
