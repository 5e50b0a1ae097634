#include "ugv/nodscan/mount.hpp"

#include <cmath>

#include "ugv/geometry/rotation.hpp"

namespace ugv::nodscan {

namespace {

// m * v summed left to right in each row. Eigen's product adds the three terms in another
// order; the points (and the simulator's rays) are compared bit for bit across versions.
Eigen::Vector3d times(const Eigen::Matrix3d& m, const Eigen::Vector3d& v)
{
    Eigen::Vector3d r;
    for (int i = 0; i < 3; ++i) r(i) = m(i, 0) * v(0) + m(i, 1) * v(1) + m(i, 2) * v(2);
    return r;
}

}  // namespace

Eigen::Matrix3d rotation_rpy(const Eigen::Vector3d& rpy)
{
    return geometry::rotation_from_euler({rpy(0), rpy(1), rpy(2)});
}

Eigen::Matrix3d tilt_rotation(double tilt)
{
    return geometry::rotation_y(tilt);
}

Eigen::Vector3d beam_direction_tilt_frame(const Eigen::Matrix3d& r_laser, double beam_angle)
{
    return times(r_laser, Eigen::Vector3d(std::cos(beam_angle), std::sin(beam_angle), 0.0));
}

Eigen::Vector3d beam_point_body(const MountGeometry& m, double tilt, double beam_angle, double range)
{
    const Eigen::Vector3d p_laser(range * std::cos(beam_angle), range * std::sin(beam_angle), 0.0);
    const Eigen::Vector3d p = times(rotation_rpy(m.laser_rpy_rad), p_laser) + m.laser_xyz_m;
    return times(rotation_rpy(m.axis_rpy_rad), times(tilt_rotation(tilt), p)) + m.axis_xyz_m;
}

Eigen::Vector3d laser_origin_body(const MountGeometry& m, double tilt)
{
    return times(rotation_rpy(m.axis_rpy_rad), times(tilt_rotation(tilt), m.laser_xyz_m)) + m.axis_xyz_m;
}

}  // namespace ugv::nodscan
