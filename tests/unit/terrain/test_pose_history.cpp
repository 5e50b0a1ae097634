#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "ugv/terrain/pose_history.hpp"

using namespace ugv::terrain;

static Pose pose_at(int64_t t_us, double x, double yaw, double var_rad2 = 0.0)
{
    Pose p;
    p.utime_us = t_us;
    p.position_m = {x, 2.0 * x, 0.5};
    p.orientation = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ());
    p.orientation_covariance_rad2 = Eigen::Matrix3d::Identity() * var_rad2;
    return p;
}

TEST_CASE("pose history interpolates position, yaw and covariance")
{
    PoseHistory h;
    REQUIRE(h.add(pose_at(1'000'000, 0.0, 0.0, 1e-4)) == PoseHistory::AddResult::added);
    REQUIRE(h.add(pose_at(1'100'000, 1.0, 0.2, 3e-4)) == PoseHistory::AddResult::added);
    Pose p;
    REQUIRE(h.at(1'025'000, p) == PoseHistory::Lookup::ok);
    CHECK(p.position_m.x() == Approx(0.25));
    CHECK(p.position_m.y() == Approx(0.5));
    CHECK(p.yaw_rad() == Approx(0.05));
    CHECK(p.orientation_error_rad2() == Approx(1.5e-4));
    CHECK(p.utime_us == 1'025'000);
    REQUIRE(h.at(1'100'000, p) == PoseHistory::Lookup::ok);
    CHECK(p.position_m.x() == 1.0);
    CHECK(h.at(999'999, p) == PoseHistory::Lookup::before_history);
    CHECK(h.at(1'100'001, p) == PoseHistory::Lookup::after_history);
}

TEST_CASE("pose history refuses non-finite and out-of-order poses and forgets old ones")
{
    PoseHistory h(500'000);
    CHECK(h.at(0, *std::make_unique<Pose>()) == PoseHistory::Lookup::empty);
    Pose bad = pose_at(0, 0.0, 0.0);
    bad.position_m.x() = std::numeric_limits<double>::quiet_NaN();
    CHECK(h.add(bad) == PoseHistory::AddResult::non_finite);
    Pose bad_cov = pose_at(0, 0.0, 0.0);
    bad_cov.orientation_covariance_rad2(2, 2) = std::numeric_limits<double>::infinity();
    CHECK(h.add(bad_cov) == PoseHistory::AddResult::non_finite);
    CHECK(h.add(pose_at(100, 0.0, 0.0)) == PoseHistory::AddResult::added);
    CHECK(h.add(pose_at(100, 1.0, 0.0)) == PoseHistory::AddResult::out_of_order);
    for (int k = 1; k <= 20; ++k) REQUIRE(h.add(pose_at(100 + k * 100'000, k, 0.0)) == PoseHistory::AddResult::added);
    CHECK(h.newest_us() == 2'000'100);
    CHECK(h.oldest_us() >= 2'000'100 - 500'000);
    CHECK(h.size() == 6);
}

TEST_CASE("orientation error is the largest of the roll, pitch and yaw variances")
{
    Pose p;
    p.orientation_covariance_rad2.diagonal() << 1e-4, 4e-4, 2e-4;
    CHECK(p.orientation_error_rad2() == 4e-4);
}
