// The 3DM-GX1's gyro-stabilised attitude as its complementary filter makes it, for the
// simulator (shared/protocols/microstrain-3dm-gx1.md, "Where the dynamic error comes from").
// The unit integrates its gyros (true rate + a drifting bias) and pulls the result toward the
// references its other sensors give, with one time constant: roll and pitch toward the
// accelerometers' "down" (specific force, so the vehicle's own acceleration tilts it) and yaw
// toward the magnetometer's heading (the field disturbed by iron, tilt-compensated with the
// filter's own roll and pitch). No I/O; time and the true motion are passed in.
#pragma once

#include <functional>
#include <random>

#include <Eigen/Core>

namespace ugv::sim::imu {

// The unit's true motion in ITS convention: roll, pitch, yaw (ZYX) of the sensor FRD axes
// relative to NED, yaw from north clockwise; angular rate in sensor FRD axes.
struct NedMotion
{
    double roll_rad = 0, pitch_rad = 0, yaw_rad = 0;
    Eigen::Vector3d rate_frd_radps = Eigen::Vector3d::Zero();
    Eigen::Vector3d accel_ned_mps2 = Eigen::Vector3d::Zero();  // kinematic acceleration (gravity apart)
};
using AttitudeFn = std::function<NedMotion(double t_s)>;

struct AhrsConfig
{
    double time_constant_s = 10.0;                 // of the pull toward the references (1 / gain)
    double gyro_bias_walk_radps_per_sqrt_s = 0.0;  // random walk of each gyro's bias, from 0 at start
    double mag_disturbance_rad = 0.0;              // amplitude of the heading-dependent yaw error
    Eigen::Vector3d mag_field_ned_gauss{0.2, 0.0, 0.45};
    double step_s = 0.005;                         // the filter's own update period
    unsigned seed = 1;
};

class AhrsModel
{
public:
    struct State
    {
        // The filter's attitude is error * R_ned_frd(truth): a rotation in NED that the gyros
        // carry along unchanged (they measure the true motion) and only the bias and the
        // pull toward the references change.
        Eigen::Matrix3d error = Eigen::Matrix3d::Identity();
        Eigen::Vector3d gyro_bias_radps = Eigen::Vector3d::Zero();  // FRD, what the rates carry
    };

    // The filter runs on the grid start_s + k * step_s (so its errors depend on the seed and
    // the truth, not on when it is asked); it starts on its references at start_s.
    AhrsModel(const AhrsConfig& config, double start_s, const AttitudeFn& truth);

    // Runs the filter up to the last grid step at or before t_s; returns its state there.
    const State& advance(double t_s);
    // The attitude the unit reports at t_s for the true motion m at t_s (after advance(t_s)).
    Eigen::Matrix3d attitude(const NedMotion& m) const;
    // The field the magnetometer measures in sensor axes (the disturbance included).
    Eigen::Vector3d measured_field(const NedMotion& m) const;
    // The magnetometer's heading error at a true (magnetic) heading.
    double heading_error_rad(double yaw_rad) const;
    const AhrsConfig& config() const { return config_; }

private:
    void step(double t_s);

    AhrsConfig config_;
    AttitudeFn truth_;
    double start_s_;
    long long steps_ = 0;  // grid steps run
    double mag_phase_rad_;
    State state_;
    std::mt19937 rng_;
    std::normal_distribution<double> gauss_{0.0, 1.0};
};

}  // namespace ugv::sim::imu
