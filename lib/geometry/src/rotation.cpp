#include "ugv/geometry/rotation.hpp"

#include <cmath>
#include <numbers>

namespace ugv::geometry {

double wrap_angle(double rad)
{
    double a = std::remainder(rad, 2.0 * std::numbers::pi);  // [-pi, pi]
    if (a <= -std::numbers::pi) {
        a += 2.0 * std::numbers::pi;
    }
    return a;
}

Eigen::Matrix2d rotation_2d(double angle)
{
    const double c = std::cos(angle), s = std::sin(angle);
    Eigen::Matrix2d r;
    r << c, -s, s, c;
    return r;
}

Eigen::Matrix3d rotation_y(double angle)
{
    const double c = std::cos(angle), s = std::sin(angle);
    Eigen::Matrix3d r;
    r << c, 0.0, s,  //
        0.0, 1.0, 0.0,  //
        -s, 0.0, c;
    return r;
}

// Through Eigen's AngleAxis (not the closed form of rotation_y): the estimator's results
// were produced with this arithmetic.
Eigen::Matrix3d rotation_z(double yaw)
{
    return Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

Eigen::Quaterniond quaternion_from_euler(const Euler& e)
{
    const Eigen::Quaterniond q = Eigen::AngleAxisd(e.yaw, Eigen::Vector3d::UnitZ()) *
                                 Eigen::AngleAxisd(e.pitch, Eigen::Vector3d::UnitY()) *
                                 Eigen::AngleAxisd(e.roll, Eigen::Vector3d::UnitX());
    return q.normalized();
}

Eigen::Matrix3d rotation_from_euler(const Euler& e)
{
    const double cr = std::cos(e.roll), sr = std::sin(e.roll);
    const double cp = std::cos(e.pitch), sp = std::sin(e.pitch);
    const double cy = std::cos(e.yaw), sy = std::sin(e.yaw);
    Eigen::Matrix3d r;
    r << cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr,  //
        sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr,    //
        -sp, cp * sr, cp * cr;
    return r;
}

double yaw_from_quaternion(const Eigen::Quaterniond& q)
{
    const Eigen::Vector3d forward = q * Eigen::Vector3d::UnitX();
    return std::atan2(forward.y(), forward.x());
}

Euler euler_from_quaternion(const Eigen::Quaterniond& q)
{
    const Eigen::Matrix3d r = q.normalized().toRotationMatrix();
    Euler e;
    // r(2,0) = -sin(pitch); clamp against rounding just beyond +-1.
    const double s = std::fmax(-1.0, std::fmin(1.0, -r(2, 0)));
    e.pitch = std::asin(s);
    e.roll = std::atan2(r(2, 1), r(2, 2));
    e.yaw = std::atan2(r(1, 0), r(0, 0));
    return e;
}

double enu_yaw_from_track(double track_rad)
{
    return wrap_angle(std::numbers::pi / 2.0 - track_rad);
}

double track_from_enu_yaw(double yaw_rad)
{
    return wrap_angle(std::numbers::pi / 2.0 - yaw_rad);
}

Eigen::Matrix3d euler_jacobian_world(const Euler& e)
{
    // A world angular velocity w relates to the Euler rates by
    //   w = roll_dot * Rz Ry e_x + pitch_dot * Rz e_y + yaw_dot * e_z,
    // so the Jacobian is the inverse of the matrix with those three columns.
    const double cy = std::cos(e.yaw), sy = std::sin(e.yaw);
    const double cp = std::cos(e.pitch), sp = std::sin(e.pitch);
    Eigen::Matrix3d m;
    m << cy * cp, -sy, 0.0,  //
        sy * cp, cy, 0.0,    //
        -sp, 0.0, 1.0;
    return m.inverse();
}

Eigen::Quaterniond quaternion_exp(const Eigen::Vector3d& v)
{
    const double angle = v.norm();
    if (angle < 1e-12) {
        // Second-order accurate for tiny angles; avoids dividing by zero.
        return Eigen::Quaterniond(1.0, 0.5 * v.x(), 0.5 * v.y(), 0.5 * v.z()).normalized();
    }
    return Eigen::Quaterniond(Eigen::AngleAxisd(angle, v / angle));
}

Eigen::Vector3d quaternion_log(const Eigen::Quaterniond& q_in)
{
    Eigen::Quaterniond q = q_in.normalized();
    if (q.w() < 0.0) {
        q.coeffs() = -q.coeffs();  // the same rotation, angle in [0, pi]
    }
    const double vn = q.vec().norm();
    if (vn < 1e-12) {
        return 2.0 * q.vec();
    }
    const double angle = 2.0 * std::atan2(vn, q.w());
    return q.vec() * (angle / vn);
}

Eigen::Matrix3d skew(const Eigen::Vector3d& a)
{
    Eigen::Matrix3d s;
    s << 0.0, -a.z(), a.y(),  //
        a.z(), 0.0, -a.x(),   //
        -a.y(), a.x(), 0.0;
    return s;
}

}  // namespace ugv::geometry
