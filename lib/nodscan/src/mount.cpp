#include "ugv/nodscan/mount.hpp"

#include <cmath>

namespace ugv::nodscan {

Mat3 rotation_rpy(double roll, double pitch, double yaw)
{
    const double cr = std::cos(roll), sr = std::sin(roll);
    const double cp = std::cos(pitch), sp = std::sin(pitch);
    const double cy = std::cos(yaw), sy = std::sin(yaw);
    return Mat3{{{cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr},
                 {sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr},
                 {-sp, cp * sr, cp * cr}}};
}

Vec3 multiply(const Mat3& m, const Vec3& v)
{
    Vec3 r{};
    for (std::size_t i = 0; i < 3; ++i) r[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
    return r;
}

Mat3 multiply(const Mat3& a, const Mat3& b)
{
    Mat3 r{};
    for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t j = 0; j < 3; ++j) r[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
    return r;
}

Mat3 tilt_rotation(double tilt)
{
    const double c = std::cos(tilt), s = std::sin(tilt);
    return Mat3{{{c, 0.0, s}, {0.0, 1.0, 0.0}, {-s, 0.0, c}}};
}

Vec3 beam_point_body(const MountGeometry& m, double tilt, double beam_angle, double range)
{
    const Vec3 p_laser{range * std::cos(beam_angle), range * std::sin(beam_angle), 0.0};
    Vec3 p = multiply(rotation_rpy(m.laser_rpy_rad[0], m.laser_rpy_rad[1], m.laser_rpy_rad[2]), p_laser);
    for (std::size_t i = 0; i < 3; ++i) p[i] += m.laser_xyz_m[i];
    p = multiply(rotation_rpy(m.axis_rpy_rad[0], m.axis_rpy_rad[1], m.axis_rpy_rad[2]), multiply(tilt_rotation(tilt), p));
    for (std::size_t i = 0; i < 3; ++i) p[i] += m.axis_xyz_m[i];
    return p;
}

Vec3 laser_origin_body(const MountGeometry& m, double tilt)
{
    Vec3 p = multiply(rotation_rpy(m.axis_rpy_rad[0], m.axis_rpy_rad[1], m.axis_rpy_rad[2]),
                      multiply(tilt_rotation(tilt), m.laser_xyz_m));
    for (std::size_t i = 0; i < 3; ++i) p[i] += m.axis_xyz_m[i];
    return p;
}

}  // namespace ugv::nodscan
