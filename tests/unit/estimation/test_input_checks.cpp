#include <catch2/catch.hpp>

#include <cmath>
#include <limits>

#include "ugv/estimation/input_checks.hpp"

using namespace ugv::estimation;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

static GpsFix good_fix()
{
    GpsFix f;
    f.utime = 1;
    f.latitude_deg = 50.0;
    f.longitude_deg = -110.0;
    f.height_m = 700.0;
    f.quality = FixQuality::dgps;
    return f;
}

TEST_CASE("fix: unknown sigmas are fine, non-finite or out-of-range positions are not")
{
    CHECK(is_valid(good_fix()));
    GpsFix f = good_fix();
    f.latitude_deg = kNaN;
    CHECK_FALSE(is_valid(f));
    f = good_fix();
    f.height_m = kInf;
    CHECK_FALSE(is_valid(f));
    f = good_fix();
    f.longitude_deg = 200.0;
    CHECK_FALSE(is_valid(f));
    f = good_fix();
    f.sigma_east_m = kInf;
    CHECK_FALSE(is_valid(f));
    f = good_fix();
    f.sigma_up_m = -1.0;
    CHECK_FALSE(is_valid(f));
    f = good_fix();
    f.utime = 0;
    CHECK_FALSE(is_valid(f));
    // A stamp beyond 2^62 us is no time; the estimator's arithmetic on stamps must not overflow.
    f = good_fix();
    f.utime = std::numeric_limits<int64_t>::max();
    CHECK_FALSE(is_valid(f));
    f.utime = int64_t{1} << 62;
    CHECK_FALSE(is_valid(f));
    f.utime = (int64_t{1} << 62) - 1;
    CHECK(is_valid(f));
}

TEST_CASE("velocity: vertical may be unknown, speed and track may not")
{
    GpsVelocity v;
    v.utime = 5;
    v.horizontal_speed_mps = 2.0;
    v.track_rad = 1.0;
    CHECK(is_valid(v));  // vertical NaN = not reported
    v.vertical_speed_mps = kInf;
    CHECK_FALSE(is_valid(v));
    v.vertical_speed_mps = 0.1;
    v.track_rad = kNaN;
    CHECK_FALSE(is_valid(v));
    v.track_rad = 1.0;
    v.horizontal_speed_mps = -1.0;
    CHECK_FALSE(is_valid(v));
}

TEST_CASE("imu: only the flagged fields are checked; the quaternion must be near unit")
{
    ImuSample s;
    s.utime = 9;
    CHECK_FALSE(is_valid(s));  // nothing present
    s.has_rate = true;
    CHECK(is_valid(s));
    s.accel_mps2.x() = kNaN;  // not flagged: ignored
    CHECK(is_valid(s));
    s.has_accel = true;
    CHECK_FALSE(is_valid(s));
    s.has_accel = false;
    s.has_orientation = true;
    s.orientation = Eigen::Quaterniond(2.0, 0.0, 0.0, 0.0);
    CHECK_FALSE(is_valid(s));
    s.orientation = Eigen::Quaterniond(1.0, 0.0, 0.0, 0.0);
    CHECK(is_valid(s));
    s.orientation_sigma_rad = 0.0;
    CHECK_FALSE(is_valid(s));
}

TEST_CASE("quality ranks")
{
    CHECK(quality_rank(FixQuality::none) == 0);
    CHECK(quality_rank(FixQuality::dead_reckoning) == 0);
    CHECK(quality_rank(FixQuality::unknown) == 0);
    CHECK(quality_rank(FixQuality::single) < quality_rank(FixQuality::dgps));
    CHECK(quality_rank(FixQuality::rtk_float) < quality_rank(FixQuality::rtk_fixed));
}
