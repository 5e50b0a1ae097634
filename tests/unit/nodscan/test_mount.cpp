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
        const Vec3 p = beam_point_body(m, t, 0.0, h / std::sin(t));
        CHECK(p[2] == Approx(0.0).margin(1e-12));
        CHECK(p[0] == Approx(0.5 + h / std::tan(t)));
        CHECK(p[1] == Approx(0.0).margin(1e-12));
        // A beam off to the side reaches the ground further away: r = h / (sin t cos a).
        const double a = 0.7;
        const Vec3 q = beam_point_body(m, t, a, h / (std::sin(t) * std::cos(a)));
        CHECK(q[2] == Approx(0.0).margin(1e-12));
        CHECK(q[1] > 0.0);  // counter-clockwise beams go left
    }
}

TEST_CASE("Axis orientation and laser offset")
{
    MountGeometry m;
    m.axis_xyz_m = {1.0, 2.0, 3.0};
    m.axis_rpy_rad = {0.0, 0.0, std::numbers::pi / 2};  // tilt unit mounted looking left
    Vec3 p = beam_point_body(m, 0.0, 0.0, 2.0);
    CHECK(p[0] == Approx(1.0));
    CHECK(p[1] == Approx(4.0));
    CHECK(p[2] == Approx(3.0));

    MountGeometry o;
    o.laser_xyz_m = {0.1, 0.0, 0.05};  // laser ahead of and above the axis
    const Vec3 level = laser_origin_body(o, 0.0);
    CHECK(level[0] == Approx(0.1));
    CHECK(level[2] == Approx(0.05));
    const Vec3 down = laser_origin_body(o, std::numbers::pi / 2);  // pointing straight down
    CHECK(down[0] == Approx(0.05));
    CHECK(down[2] == Approx(-0.1));
}

TEST_CASE("rpy rotation is Rz(yaw) Ry(pitch) Rx(roll)")
{
    const Mat3 r = rotation_rpy(0.1, 0.2, 0.3);
    const Mat3 expected = multiply(rotation_rpy(0, 0, 0.3), multiply(rotation_rpy(0, 0.2, 0), rotation_rpy(0.1, 0, 0)));
    for (std::size_t i = 0; i < 3; ++i)
        for (std::size_t j = 0; j < 3; ++j) CHECK(r[i][j] == Approx(expected[i][j]).margin(1e-15));
    // A positive pitch turns +X down, as a positive tilt does.
    const Vec3 x = multiply(rotation_rpy(0, 0.3, 0), Vec3{1, 0, 0});
    const Vec3 y = multiply(tilt_rotation(0.3), Vec3{1, 0, 0});
    CHECK(x[2] < 0);
    CHECK(x[2] == Approx(y[2]));
}
