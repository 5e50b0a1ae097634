#include <catch2/catch.hpp>

#include <numbers>

#include "ugv/geometry/pose.hpp"
#include "ugv/geometry/rotation.hpp"

using namespace ugv::geometry;

TEST_CASE("rigid transform composes and inverts")
{
    RigidTransform a{quaternion_from_euler({0.1, 0.2, 0.3}), {1.0, 2.0, 3.0}};
    RigidTransform b{quaternion_from_euler({-0.2, 0.0, 1.0}), {-1.0, 0.5, 0.0}};
    const Eigen::Vector3d x(0.3, -0.7, 2.0);
    CHECK(((a * b).apply(x) - a.apply(b.apply(x))).norm() < 1e-12);
    CHECK((a.inverse().apply(a.apply(x)) - x).norm() < 1e-12);
    // A body point 1 m ahead of a vehicle at (10, 0) facing north is at (10, 1).
    RigidTransform north{quaternion_from_euler({0, 0, std::numbers::pi / 2}), {10.0, 0.0, 0.0}};
    const Eigen::Vector3d p = north.apply(Eigen::Vector3d::UnitX());
    CHECK(p.x() == Approx(10.0));
    CHECK(p.y() == Approx(1.0));
}

TEST_CASE("interpolate: position linear, orientation slerp")
{
    StampedPose a{1'000'000, {quaternion_from_euler({0, 0, 0.0}), {0.0, 0.0, 0.0}}};
    StampedPose b{2'000'000, {quaternion_from_euler({0, 0, 1.0}), {10.0, -4.0, 2.0}}};
    const StampedPose m = interpolate(a, b, 1'250'000);
    CHECK(m.utime == 1'250'000);
    CHECK(m.body_to_world.translation.x() == Approx(2.5));
    CHECK(m.body_to_world.translation.y() == Approx(-1.0));
    CHECK(m.body_to_world.translation.z() == Approx(0.5));
    CHECK(euler_from_quaternion(m.body_to_world.rotation).yaw == Approx(0.25));
    // The end points come back exactly.
    CHECK(euler_from_quaternion(interpolate(a, b, 2'000'000).body_to_world.rotation).yaw == Approx(1.0));
    // Equal stamps: the first pose.
    CHECK(interpolate(a, a, 5).body_to_world.translation.norm() == 0.0);
}
