#include "ugv/microstrain_gx1/orientation.hpp"

#include <algorithm>
#include <cmath>

namespace ugv::microstrain_gx1 {

namespace {

// FLU -> FRD (and back): a half turn about X.
const Eigen::Matrix3d& flip_yz()
{
    static const Eigen::Matrix3d f = Eigen::Vector3d(1, -1, -1).asDiagonal();
    return f;
}

// NED -> ENU: east = ned.y, north = ned.x, up = -ned.z.
const Eigen::Matrix3d& ned_to_enu()
{
    static const Eigen::Matrix3d n = (Eigen::Matrix3d() << 0, 1, 0, 1, 0, 0, 0, 0, -1).finished();
    return n;
}

}  // namespace

Eigen::Matrix3d rotation_from_euler(double roll, double pitch, double yaw)
{
    return (Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
            Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()))
        .toRotationMatrix();
}

Eigen::Vector3d euler_from_rotation(const Eigen::Matrix3d& r)
{
    const double pitch = std::asin(std::clamp(-r(2, 0), -1.0, 1.0));
    const double roll = std::atan2(r(2, 1), r(2, 2));
    const double yaw = std::atan2(r(1, 0), r(0, 0));
    return {roll, pitch, yaw};
}

Eigen::Matrix3d enu_flu_from_ned_frd(const Eigen::Matrix3d& r_ned_frd, double declination_rad)
{
    const Eigen::Matrix3d true_north = Eigen::AngleAxisd(declination_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return ned_to_enu() * true_north * r_ned_frd * flip_yz();
}

EnuAttitude attitude_from_rotation(const Eigen::Matrix3d& r_enu_body)
{
    EnuAttitude a;
    a.q_enu_body = Eigen::Quaterniond(r_enu_body).normalized();
    if (a.q_enu_body.w() < 0) a.q_enu_body.coeffs() *= -1.0;  // one sign for the same rotation
    const Eigen::Vector3d rpy = euler_from_rotation(r_enu_body);
    a.roll_rad = rpy.x();
    a.pitch_rad = rpy.y();
    a.yaw_rad = rpy.z();
    return a;
}

EnuAttitude enu_from_ned_euler(double roll, double pitch, double yaw, double declination_rad)
{
    return attitude_from_rotation(enu_flu_from_ned_frd(rotation_from_euler(roll, pitch, yaw), declination_rad));
}

EnuAttitude enu_from_ned_quaternion(const Eigen::Quaterniond& q_ned_frd, double declination_rad)
{
    return attitude_from_rotation(enu_flu_from_ned_frd(q_ned_frd.normalized().toRotationMatrix(), declination_rad));
}

FrameConverter::FrameConverter(const Eigen::Matrix3d& r_body_sensor, double declination_rad)
    : r_body_sensor_(r_body_sensor), declination_rad_(declination_rad)
{
}

Measurement FrameConverter::convert(const DeviceSample& s) const
{
    Measurement m;
    bool have_rotation = true;
    Eigen::Matrix3d r_ned_frd;
    if (s.has_euler) {
        r_ned_frd = rotation_from_euler(s.roll_rad, s.pitch_rad, s.yaw_rad);
    } else if (s.has_quaternion) {
        const auto& q = s.quaternion;
        r_ned_frd = Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
    } else if (s.has_matrix) {
        Eigen::Matrix3d m_ned_to_sensor;
        for (int i = 0; i < 9; ++i) m_ned_to_sensor(i / 3, i % 3) = s.matrix[static_cast<std::size_t>(i)];
        r_ned_frd = m_ned_to_sensor.transpose();
    } else {
        have_rotation = false;
    }
    if (have_rotation) {
        const Eigen::Matrix3d r_enu_sensor = enu_flu_from_ned_frd(r_ned_frd, declination_rad_);
        m.attitude = attitude_from_rotation(r_enu_sensor * r_body_sensor_.transpose());
        m.has_orientation = true;
    }
    auto to_body = [this](const std::array<double, 3>& v) {
        return Eigen::Vector3d(r_body_sensor_ * flu_from_frd(Eigen::Vector3d(v[0], v[1], v[2])));
    };
    if (s.has_rate) {
        m.rate_radps = to_body(s.rate_radps);
        m.has_rate = true;
    }
    if (s.has_accel) {
        m.accel_mps2 = to_body(s.accel_mps2);
        m.has_accel = true;
    }
    if (s.has_mag) {
        m.mag_gauss = to_body(s.mag_gauss);
        m.has_mag = true;
    }
    return m;
}

}  // namespace ugv::microstrain_gx1
