#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>

#include "ugv/geometry/rotation.hpp"

using namespace ugv::geometry;
constexpr double kPi = std::numbers::pi;

TEST_CASE("wrap_angle maps into (-pi, pi]")
{
    CHECK(wrap_angle(0.0) == 0.0);
    CHECK(wrap_angle(kPi) == Approx(kPi));
    CHECK(wrap_angle(-kPi) == Approx(kPi));
    CHECK(wrap_angle(3.0 * kPi / 2.0) == Approx(-kPi / 2.0));
    CHECK(wrap_angle(-7.0 * kPi / 2.0) == Approx(kPi / 2.0));
    CHECK(wrap_angle(0.1 + 20.0 * kPi) == Approx(0.1));
}

TEST_CASE("yaw 90 deg turns body X (forward) to ENU north, body Y (left) to west")
{
    const Eigen::Matrix3d r = rotation_from_euler({0.0, 0.0, kPi / 2.0});
    const Eigen::Vector3d fwd = r * Eigen::Vector3d::UnitX();
    const Eigen::Vector3d left = r * Eigen::Vector3d::UnitY();
    CHECK(fwd.x() == Approx(0.0).margin(1e-15));
    CHECK(fwd.y() == Approx(1.0));
    CHECK(left.x() == Approx(-1.0));
    CHECK(left.y() == Approx(0.0).margin(1e-15));
}

TEST_CASE("positive pitch tips the nose down, positive roll drops the right side")
{
    // Right-handed rotation about +Y (left) moves +X (forward) toward -Z (down).
    const Eigen::Vector3d fwd = rotation_from_euler({0.0, 0.2, 0.0}) * Eigen::Vector3d::UnitX();
    CHECK(fwd.z() == Approx(-std::sin(0.2)));
    // Right-handed rotation about +X (forward) moves +Y (left) upward.
    const Eigen::Vector3d left = rotation_from_euler({0.3, 0.0, 0.0}) * Eigen::Vector3d::UnitY();
    CHECK(left.z() == Approx(std::sin(0.3)));
}

TEST_CASE("Euler -> quaternion -> Euler round trip")
{
    for (double roll : {-1.0, -0.1, 0.0, 0.4}) {
        for (double pitch : {-1.2, 0.0, 0.3, 1.4}) {
            for (double yaw : {-3.0, -1.0, 0.0, 2.0, 3.1}) {
                const Euler e = euler_from_quaternion(quaternion_from_euler({roll, pitch, yaw}));
                CHECK(e.roll == Approx(roll).margin(1e-12));
                CHECK(e.pitch == Approx(pitch).margin(1e-12));
                CHECK(e.yaw == Approx(yaw).margin(1e-12));
            }
        }
    }
}

TEST_CASE("GPS track (clockwise from north) <-> ENU yaw (counter-clockwise from east)")
{
    CHECK(enu_yaw_from_track(0.0) == Approx(kPi / 2.0));        // north
    CHECK(enu_yaw_from_track(kPi / 2.0) == Approx(0.0));        // east
    CHECK(enu_yaw_from_track(kPi) == Approx(-kPi / 2.0));       // south
    CHECK(enu_yaw_from_track(3.0 * kPi / 2.0) == Approx(kPi));  // west
    CHECK(track_from_enu_yaw(enu_yaw_from_track(0.7)) == Approx(0.7));
}

TEST_CASE("exp and log of rotation vectors are inverse")
{
    const Eigen::Vector3d v(0.3, -0.2, 1.1);
    const Eigen::Vector3d back = quaternion_log(quaternion_exp(v));
    CHECK((back - v).norm() < 1e-12);
    const Eigen::Vector3d tiny(1e-14, 0.0, -2e-14);
    CHECK((quaternion_log(quaternion_exp(tiny)) - tiny).norm() < 1e-20);
    // exp about z by a is the yaw rotation by a.
    CHECK((quaternion_exp(Eigen::Vector3d(0, 0, 0.5)).toRotationMatrix() - rotation_z(0.5)).norm() < 1e-15);
}

TEST_CASE("skew is the cross product")
{
    const Eigen::Vector3d a(1, 2, 3), b(-4, 0.5, 2);
    CHECK((skew(a) * b - a.cross(b)).norm() < 1e-15);
}

TEST_CASE("euler_jacobian_world matches finite differences")
{
    const Euler e{0.2, -0.3, 2.5};
    const Eigen::Quaterniond q = quaternion_from_euler(e);
    const Eigen::Matrix3d j = euler_jacobian_world(e);
    const double h = 1e-7;
    for (int k = 0; k < 3; ++k) {
        Eigen::Vector3d d = Eigen::Vector3d::Zero();
        d(k) = h;
        const Euler ep = euler_from_quaternion(quaternion_exp(d) * q);
        const Eigen::Vector3d num((ep.roll - e.roll) / h, (ep.pitch - e.pitch) / h,
                                  wrap_angle(ep.yaw - e.yaw) / h);
        CHECK((num - j.col(k)).norm() < 1e-5);
    }
    // At zero roll and pitch a world rotation about up is a pure yaw change.
    const Eigen::Matrix3d flat = euler_jacobian_world({0.0, 0.0, 1.0});
    CHECK(flat(2, 2) == Approx(1.0));
    CHECK(flat(2, 0) == Approx(0.0).margin(1e-15));
}
