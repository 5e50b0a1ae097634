#include "ugv/nodscan/mount_config.hpp"

#include <numbers>

namespace ugv::nodscan {

namespace {

Eigen::Vector3d vec3(const std::vector<double>& v, double scale = 1.0)
{
    return Eigen::Vector3d(v[0] * scale, v[1] * scale, v[2] * scale);
}

}  // namespace

MountGeometry read_mount(runtime::Config& m)
{
    constexpr double kDeg = std::numbers::pi / 180.0;
    MountGeometry g;
    g.axis_xyz_m = vec3(m.get_doubles("tilt_axis_xyz_m", {0.0, 0.0, 0.87}, 3, -10.0, 10.0));
    g.axis_rpy_rad = vec3(m.get_doubles("tilt_axis_rpy_deg", {0.0, 0.0, 0.0}, 3, -180.0, 180.0), kDeg);
    g.laser_xyz_m = vec3(m.get_doubles("laser_xyz_m", {0.0, 0.0, 0.0}, 3, -2.0, 2.0));
    g.laser_rpy_rad = vec3(m.get_doubles("laser_rpy_deg", {0.0, 0.0, 0.0}, 3, -180.0, 180.0), kDeg);
    return g;
}

}  // namespace ugv::nodscan
