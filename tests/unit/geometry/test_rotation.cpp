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

TEST_CASE("wrap_angle at the +-pi boundary: +pi stays, -pi becomes +pi, just past wraps over")
{
    CHECK(wrap_angle(kPi) == kPi);
    CHECK(wrap_angle(-kPi) == kPi);
    const double below = std::nextafter(-kPi, 0.0);  // just inside at the bottom
    CHECK(wrap_angle(below) == below);
    const double above = std::nextafter(kPi, 4.0);  // just outside at the top
    CHECK(wrap_angle(above) < -kPi + 1e-15);
    CHECK(wrap_angle(above) > -kPi);
    CHECK(wrap_angle(3.0 * kPi) == Approx(kPi));
    CHECK(wrap_angle(-3.0 * kPi) > 0.0);
    for (double a = -10.0; a <= 10.0; a += 0.37) {
        const double w = wrap_angle(a);
        CHECK(w > -kPi);
        CHECK(w <= kPi);
        CHECK(std::cos(w) == Approx(std::cos(a)).margin(1e-12));
        CHECK(std::sin(w) == Approx(std::sin(a)).margin(1e-12));
    }
}

TEST_CASE("rotation matrix from Euler angles is the quaternion's rotation, Rz Ry Rx")
{
    for (const Euler e : {Euler{0.1, 0.2, 0.3}, Euler{-1.0, 1.2, -3.1}, Euler{0.4, -0.3, 3.14}}) {
        const Eigen::Matrix3d r = rotation_from_euler(e);
        CHECK((r - quaternion_from_euler(e).toRotationMatrix()).norm() < 1e-15);
        const Eigen::Matrix3d zyx = rotation_z(e.yaw) * rotation_y(e.pitch) *
                                    Eigen::AngleAxisd(e.roll, Eigen::Vector3d::UnitX()).toRotationMatrix();
        CHECK((r - zyx).norm() < 1e-15);
        CHECK((r * r.transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-15);
        // And back.
        const Euler b = euler_from_quaternion(Eigen::Quaterniond(r));
        CHECK(b.roll == Approx(e.roll));
        CHECK(b.pitch == Approx(e.pitch));
        CHECK(b.yaw == Approx(e.yaw));
    }
    // Zero angles give the identity exactly (a mount with no rotation adds no rounding).
    CHECK(rotation_from_euler({0.0, 0.0, 0.0}) == Eigen::Matrix3d::Identity());
}

TEST_CASE("rotation_y and rotation_2d: directions and round trips")
{
    // A positive angle about +Y turns +X towards -Z.
    CHECK((rotation_y(0.3) * Eigen::Vector3d::UnitX()).z() == Approx(-std::sin(0.3)));
    CHECK((rotation_y(0.3) - Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()).toRotationMatrix()).norm() < 1e-15);
    CHECK((rotation_y(-0.7) * rotation_y(0.7) - Eigen::Matrix3d::Identity()).norm() < 1e-15);
    // Counter-clockwise in the plane: +x turns towards +y.
    const Eigen::Vector2d v = rotation_2d(kPi / 2.0) * Eigen::Vector2d(1.0, 0.0);
    CHECK(v.x() == Approx(0.0).margin(1e-15));
    CHECK(v.y() == Approx(1.0));
    CHECK((rotation_2d(2.5) * rotation_2d(-2.5) - Eigen::Matrix2d::Identity()).norm() < 1e-15);
    CHECK((rotation_2d(1.1) - rotation_z(1.1).topLeftCorner<2, 2>()).norm() < 1e-15);
}

TEST_CASE("yaw_from_quaternion is the Z-Y-X yaw, also next to +-pi")
{
    for (double yaw : {-kPi, -3.1, -1.0, 0.0, 2.0, 3.1, kPi}) {
        for (double pitch : {-0.4, 0.0, 0.3}) {
            const Eigen::Quaterniond q = quaternion_from_euler({0.2, pitch, yaw});
            CHECK(std::cos(yaw_from_quaternion(q) - yaw) == Approx(1.0));
            CHECK(yaw_from_quaternion(q) == Approx(euler_from_quaternion(q).yaw).margin(1e-12));
        }
    }
    // The quaternion's sign does not matter.
    const Eigen::Quaterniond q = quaternion_from_euler({0.0, 0.0, 3.0});
    CHECK(yaw_from_quaternion(Eigen::Quaterniond(-q.coeffs())) == Approx(3.0));
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
