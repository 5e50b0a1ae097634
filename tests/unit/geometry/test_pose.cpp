#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
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

namespace {

StampedPose pose_at(int64_t t_us, double x, double yaw, double var_rad2 = 0.0)
{
    StampedPose p;
    p.utime_us = t_us;
    p.position_m = {x, -2.0 * x, 0.5};
    p.orientation = quaternion_from_euler({0.0, 0.0, yaw});
    p.orientation_covariance_rad2 = Eigen::Matrix3d::Identity() * var_rad2;
    return p;
}

}  // namespace

TEST_CASE("interpolate: position and covariance linear, orientation slerp, time rounded")
{
    const StampedPose a = pose_at(1'000'000, 0.0, 0.0, 1e-4);
    const StampedPose b = pose_at(2'000'001, 10.0, 1.0, 3e-4);
    const StampedPose m = interpolate(a, b, 0.25);
    CHECK(m.utime_us == 1'250'000);  // 250000.25 rounds down
    CHECK(m.position_m.x() == Approx(2.5));
    CHECK(m.position_m.y() == Approx(-5.0));
    CHECK(m.position_m.z() == Approx(0.5));
    CHECK(m.yaw_rad() == Approx(0.25));
    CHECK(m.orientation_covariance_rad2(2, 2) == Approx(1.5e-4));
    // The end points come back.
    CHECK(interpolate(a, b, 0.0).position_m == a.position_m);
    CHECK(interpolate(a, b, 1.0).yaw_rad() == Approx(1.0));
    CHECK(interpolate(a, b, 1.0).utime_us == b.utime_us);
}

TEST_CASE("interpolate: yaw across +-pi goes the short way")
{
    const double deg = std::numbers::pi / 180.0;
    const StampedPose a = pose_at(0, 0.0, 170.0 * deg);
    const StampedPose b = pose_at(100, 0.0, -170.0 * deg);
    CHECK(std::abs(interpolate(a, b, 0.5).yaw_rad()) == Approx(std::numbers::pi));
    CHECK(interpolate(a, b, 0.25).yaw_rad() == Approx(175.0 * deg));
    CHECK(interpolate(a, b, 0.75).yaw_rad() == Approx(-175.0 * deg));
    // The quaternions of b and -b are the same rotation: still the short way.
    StampedPose b_neg = b;
    b_neg.orientation.coeffs() = -b.orientation.coeffs();
    CHECK(interpolate(a, b_neg, 0.25).yaw_rad() == Approx(175.0 * deg));
}

TEST_CASE("stamped pose: finiteness, yaw and the orientation error bound")
{
    StampedPose p = pose_at(0, 1.0, -2.0);
    CHECK(p.finite());
    CHECK(p.yaw_rad() == Approx(-2.0));
    p.orientation_covariance_rad2.diagonal() << 1e-4, 4e-4, 2e-4;
    CHECK(p.orientation_error_rad2() == 4e-4);
    p.orientation_covariance_rad2.diagonal() << -1e-4, -2e-4, -3e-4;  // not a covariance: no negative bound
    CHECK(p.orientation_error_rad2() == 0.0);
    p.orientation = Eigen::Quaterniond(0.1, 0.0, 0.0, 0.0);
    CHECK_FALSE(p.finite());  // degenerate orientation
    p = pose_at(0, 1.0, 0.0);
    p.position_m.z() = std::numeric_limits<double>::quiet_NaN();
    CHECK_FALSE(p.finite());
}
