#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "ugv/nodscan/mount.hpp"

using namespace ugv::nodscan;
using Catch::Detail::Approx;

TEST_CASE("A level laser at height h tilted down by t sees flat ground at range h / sin(t)")
{
    const double h = 0.87;
    MountGeometry m;
    m.axis_xyz_m = {0.5, 0.0, h};
    for (double t : {0.05, 0.2, 0.6, 1.2}) {
        const Eigen::Vector3d p = beam_point_body(m, t, 0.0, h / std::sin(t));
        CHECK(p[2] == Approx(0.0).margin(1e-12));
        CHECK(p[0] == Approx(0.5 + h / std::tan(t)));
        CHECK(p[1] == Approx(0.0).margin(1e-12));
        // A beam off to the side reaches the ground further away: r = h / (sin t cos a).
        const double a = 0.7;
        const Eigen::Vector3d q = beam_point_body(m, t, a, h / (std::sin(t) * std::cos(a)));
        CHECK(q[2] == Approx(0.0).margin(1e-12));
        CHECK(q[1] > 0.0);  // counter-clockwise beams go left
    }
}

TEST_CASE("Axis orientation and laser offset")
{
    MountGeometry m;
    m.axis_xyz_m = {1.0, 2.0, 3.0};
    m.axis_rpy_rad = {0.0, 0.0, std::numbers::pi / 2};  // tilt unit mounted looking left
    const Eigen::Vector3d p = beam_point_body(m, 0.0, 0.0, 2.0);
    CHECK(p[0] == Approx(1.0));
    CHECK(p[1] == Approx(4.0));
    CHECK(p[2] == Approx(3.0));

    MountGeometry o;
    o.laser_xyz_m = {0.1, 0.0, 0.05};  // laser ahead of and above the axis
    const Eigen::Vector3d level = laser_origin_body(o, 0.0);
    CHECK(level[0] == Approx(0.1));
    CHECK(level[2] == Approx(0.05));
    const Eigen::Vector3d down = laser_origin_body(o, std::numbers::pi / 2);  // pointing straight down
    CHECK(down[0] == Approx(0.05));
    CHECK(down[2] == Approx(-0.1));
}

TEST_CASE("A positive tilt turns the beam down as a positive pitch of the mount does")
{
    const Eigen::Vector3d x = rotation_rpy({0.0, 0.3, 0.0}) * Eigen::Vector3d::UnitX();
    const Eigen::Vector3d y = tilt_rotation(0.3) * Eigen::Vector3d::UnitX();
    CHECK(x.z() < 0);
    CHECK(x.z() == Approx(y.z()));
    CHECK(x.x() == Approx(y.x()));
}

TEST_CASE("The beam direction in the tilt frame is the laser's rotation of the scan-plane beam")
{
    const Eigen::Matrix3d r_laser = rotation_rpy({0.01, 0.03, -0.02});
    const Eigen::Vector3d u = beam_direction_tilt_frame(r_laser, 0.4);
    CHECK((u - r_laser * Eigen::Vector3d(std::cos(0.4), std::sin(0.4), 0.0)).norm() < 1e-15);
    CHECK(u.norm() == Approx(1.0));
}
