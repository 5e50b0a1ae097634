#include "ahrs_model.hpp"

#include <cmath>

#include <Eigen/Geometry>

#include "ugv/microstrain_gx1/orientation.hpp"

namespace ugv::sim::imu {

namespace gx1 = ugv::microstrain_gx1;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kGravity = 9.80665;
const Eigen::Vector3d kDown(0.0, 0.0, 1.0);

Eigen::Matrix3d rotation_of(const NedMotion& m)
{
    return gx1::rotation_from_euler(m.roll_rad, m.pitch_rad, m.yaw_rad);
}

// "Down" in sensor axes as the accelerometers see it: against the specific force.
Eigen::Vector3d measured_down(const NedMotion& m, const Eigen::Matrix3d& r_true)
{
    const Eigen::Vector3d f = r_true.transpose() * (m.accel_ned_mps2 - kGravity * kDown);
    return -f.normalized();
}

// Heading from a sensor-axes field, levelled with the given roll and pitch.
double heading_of(const Eigen::Vector3d& field_sensor, double roll, double pitch)
{
    const Eigen::Vector3d level = (Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                                   Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX())) *
                                  field_sensor;
    return std::atan2(-level.y(), level.x());
}

}  // namespace

AhrsModel::AhrsModel(const AhrsConfig& config, double start_s, const AttitudeFn& truth)
    : config_(config), truth_(truth), start_s_(start_s), rng_(config.seed)
{
    mag_phase_rad_ = std::uniform_real_distribution<double>(-kPi, kPi)(rng_);
    // Power-on: the filter starts on its references (gravity and the disturbed heading).
    const NedMotion m = truth_(start_s);
    const Eigen::Matrix3d r = rotation_of(m);
    const Eigen::Vector3d d = measured_down(m, r);
    const double roll = std::atan2(d.y(), d.z()), pitch = std::atan2(-d.x(), std::hypot(d.y(), d.z()));
    const double yaw = heading_of(measured_field(m), roll, pitch);
    state_.error = gx1::rotation_from_euler(roll, pitch, yaw) * r.transpose();
    step(start_s);
}

double AhrsModel::heading_error_rad(double yaw_rad) const
{
    return config_.mag_disturbance_rad * std::sin(yaw_rad + mag_phase_rad_);
}

Eigen::Vector3d AhrsModel::measured_field(const NedMotion& m) const
{
    // The field turned by minus the error about down: the heading computed from it is off by +error.
    const Eigen::Matrix3d turn(Eigen::AngleAxisd(-heading_error_rad(m.yaw_rad), kDown));
    return rotation_of(m).transpose() * (turn * config_.mag_field_ned_gauss);
}

Eigen::Matrix3d AhrsModel::attitude(const NedMotion& m) const
{
    return state_.error * rotation_of(m);
}

const AhrsModel::State& AhrsModel::advance(double t_s)
{
    while (start_s_ + static_cast<double>(steps_) * config_.step_s <= t_s)
        step(start_s_ + static_cast<double>(steps_) * config_.step_s);
    return state_;
}

void AhrsModel::step(double t_s)
{
    const double h = config_.step_s, gain = 1.0 / config_.time_constant_s;
    const NedMotion m = truth_(t_s);
    const Eigen::Matrix3d r = rotation_of(m);
    const Eigen::Matrix3d r_est = state_.error * r;
    // Tilt: turn the estimated down toward the accelerometers' (Mahony's measured x estimated).
    const Eigen::Vector3d down_est = r_est.transpose() * kDown;
    Eigen::Vector3d correction = gain * measured_down(m, r).cross(down_est);
    // Yaw: about down, toward the magnetometer's heading levelled with the filter's own tilt.
    const Eigen::Vector3d rpy = gx1::euler_from_rotation(r_est);
    const double yaw_error = std::remainder(heading_of(measured_field(m), rpy.x(), rpy.y()) - rpy.z(), 2 * kPi);
    correction += gain * yaw_error * down_est;
    // The gyros measure the true rate plus their bias: beyond the true motion the filter turns
    // by the bias and the correction (body axes), i.e. by r * that in NED.
    const Eigen::Vector3d turn_ned = r * ((state_.gyro_bias_radps + correction) * h);
    if (turn_ned.norm() > 0) {
        Eigen::Quaterniond q(state_.error);
        q = q * Eigen::Quaterniond(Eigen::AngleAxisd(turn_ned.norm(), turn_ned.normalized()));
        state_.error = q.normalized().toRotationMatrix();
    }
    const double walk = config_.gyro_bias_walk_radps_per_sqrt_s * std::sqrt(h);
    if (walk > 0)
        for (int i = 0; i < 3; ++i) state_.gyro_bias_radps[i] += walk * gauss_(rng_);
    ++steps_;
}

}  // namespace ugv::sim::imu
