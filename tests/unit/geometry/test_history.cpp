#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <numbers>

#include "ugv/geometry/history.hpp"
#include "ugv/geometry/pose_history.hpp"
#include "ugv/geometry/rotation.hpp"

using namespace ugv::geometry;

namespace {

struct Tick
{
    int64_t utime_us = 0;
    int value = 0;
};

StampedPose pose_at(int64_t t_us, double x, double yaw)
{
    StampedPose p;
    p.utime_us = t_us;
    p.position_m = {x, 0.0, 0.0};
    p.orientation = quaternion_from_euler({0.0, 0.0, yaw});
    return p;
}

}  // namespace

TEST_CASE("time history: strictly increasing stamps, bounded by its span, two kept")
{
    TimeHistory<Tick> h(100);
    CHECK(h.empty());
    CHECK(h.add({10, 1}));
    CHECK_FALSE(h.add({10, 2}));  // same stamp
    CHECK_FALSE(h.add({5, 3}));   // older
    CHECK(h.size() == 1);
    CHECK(h.newest().value == 1);
    // A long gap: the span would leave only the new sample, but two are kept.
    CHECK(h.add({1'000, 4}));
    CHECK(h.size() == 2);
    CHECK(h.oldest().utime_us == 10);
    for (int64_t t = 1'010; t <= 1'200; t += 10) REQUIRE(h.add({t, 0}));
    CHECK(h.newest().utime_us == 1'200);
    CHECK(h.oldest().utime_us == 1'100);  // nothing older than newest - span
    CHECK(h.size() == 11);
    h.clear();
    CHECK(h.empty());
}

TEST_CASE("time history: the first sample not before a time")
{
    TimeHistory<Tick> h(1'000);
    for (int64_t t : {100, 200, 300}) h.add({t, 0});
    CHECK(h.first_not_before(50) == 0);
    CHECK(h.first_not_before(100) == 0);
    CHECK(h.first_not_before(101) == 1);
    CHECK(h.first_not_before(300) == 2);
    CHECK(h.first_not_before(301) == 3);  // after all of them
    CHECK(h[1].utime_us == 200);
}

TEST_CASE("pose history: exact at the stored poses, interpolated between, nothing outside")
{
    PoseHistory h;
    StampedPose p;
    CHECK(h.at(0, p) == PoseHistory::Lookup::empty);
    REQUIRE(h.add(pose_at(1'000'000, 0.0, 3.0)) == PoseHistory::AddResult::added);
    REQUIRE(h.add(pose_at(1'100'000, 1.0, -3.0)) == PoseHistory::AddResult::added);
    REQUIRE(h.at(1'100'000, p) == PoseHistory::Lookup::ok);
    CHECK(p.position_m.x() == 1.0);
    REQUIRE(h.at(1'025'000, p) == PoseHistory::Lookup::ok);
    CHECK(p.utime_us == 1'025'000);
    CHECK(p.position_m.x() == Approx(0.25));
    // 3.0 -> -3.0 rad is 0.283 rad the short way, across +pi.
    const double short_way = 2.0 * std::numbers::pi - 6.0;
    CHECK(wrap_angle(p.yaw_rad() - 3.0) == Approx(0.25 * short_way));
    CHECK(h.at(999'999, p) == PoseHistory::Lookup::before_history);
    CHECK(h.at(1'100'001, p) == PoseHistory::Lookup::after_history);
}

TEST_CASE("pose history: refuses non-finite and out-of-order poses, stores a unit quaternion")
{
    PoseHistory h(500'000);
    StampedPose bad = pose_at(0, 0.0, 0.0);
    bad.orientation_covariance_rad2(1, 1) = std::numeric_limits<double>::infinity();
    CHECK(h.add(bad) == PoseHistory::AddResult::non_finite);
    StampedPose tiny = pose_at(0, 0.0, 0.0);
    tiny.orientation.coeffs() *= 0.4;  // would normalise, but is refused
    CHECK(h.add(tiny) == PoseHistory::AddResult::non_finite);
    StampedPose scaled = pose_at(100, 0.0, 0.5);
    scaled.orientation.coeffs() *= 2.0;
    CHECK(h.add(scaled) == PoseHistory::AddResult::added);
    CHECK(h.newest().orientation.norm() == Approx(1.0));
    CHECK(h.add(pose_at(100, 1.0, 0.0)) == PoseHistory::AddResult::out_of_order);
    for (int k = 1; k <= 20; ++k) REQUIRE(h.add(pose_at(100 + k * 100'000, k, 0.0)) == PoseHistory::AddResult::added);
    CHECK(h.newest_us() == 2'000'100);
    CHECK(h.oldest_us() == 1'500'100);
    CHECK(h.size() == 6);
}

TEST_CASE("TimeHistory keeps at most max_samples whatever the stamps, and takes the int64 extremes")
{
    TimeHistory<Tick> h(2'000'000, 100);
    for (int k = 0; k < 1000; ++k) REQUIRE(h.add({1'000'000'000 + k, k}));  // 1 us apart: all in the span
    CHECK(h.size() == 100);
    CHECK(h.oldest().value == 900);
    CHECK(h.newest().value == 999);

    TimeHistory<Tick> extremes(2'000'000);
    CHECK(extremes.add({std::numeric_limits<int64_t>::min(), 0}));
    CHECK(extremes.add({std::numeric_limits<int64_t>::min() + 1, 1}));
    CHECK(extremes.add({0, 2}));
    CHECK(extremes.add({std::numeric_limits<int64_t>::max(), 3}));
    CHECK(extremes.size() == 2);  // the span drops all but the last two
    CHECK_FALSE(extremes.add({std::numeric_limits<int64_t>::max(), 4}));
}
