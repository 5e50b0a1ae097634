#include <catch2/catch.hpp>

#include "ugv/novatel/enums.hpp"
#include "ugv/novatel/gps_time.hpp"

using namespace ugv::novatel;

TEST_CASE("gps_to_unix_utime: known instants")
{
    // GPS epoch with no leap seconds is 1980-01-06T00:00:00Z.
    CHECK(gps_to_unix_utime(0, 0, 0) == 315964800LL * 1'000'000);
    // Week 2080, 412623.400 s (the swri capture), 18 leap seconds:
    // 315964800 + 2080*604800 + 412623.4 - 18 = 1574361405.4 s = 2019-11-21T18:36:45.4Z
    CHECK(gps_to_unix_utime(2080, 412623400, 18) == 1574361405'400'000LL);
    CHECK(gps_to_unix_utime(2080, 412623400, 17) == 1574361406'400'000LL);
}

TEST_CASE("unix_utime_to_gps inverts gps_to_unix_utime")
{
    uint32_t week = 0, ms = 0;
    unix_utime_to_gps(1574361405'400'000LL, 18, week, ms);
    CHECK(week == 2080);
    CHECK(ms == 412623400);
}

TEST_CASE("utc_time_of_day_to_utime takes the day nearest the arrival time, across midnight")
{
    const int64_t day = 1573862400LL * 1'000'000;  // 2019-11-16T00:00:00Z
    // Arrival 0.3 s after the measurement, same day.
    CHECK(utc_time_of_day_to_utime(61385.4, day + 61'385'700'000LL) == day + 61'385'400'000LL);
    // Measured at 23:59:59.9, arrived just after midnight: the previous day.
    CHECK(utc_time_of_day_to_utime(86399.9, day + 200'000LL) == day - 100'000LL);
    // Host clock slightly behind: measured 00:00:00.1, arrived (host) 23:59:59.95 the day before.
    CHECK(utc_time_of_day_to_utime(0.1, day - 50'000LL) == day + 100'000LL);
}

TEST_CASE("utc_date_to_utime")
{
    CHECK(utc_date_to_utime(2017, 7, 12, 22 * 3600 + 23 * 60 + 6.75) == 1499898186'750'000LL);
    CHECK(utc_date_to_utime(1970, 1, 1, 0.0) == 0);
}

TEST_CASE("time_status_is_fine: FINE or better")
{
    CHECK(time_status_is_fine(time_status::fine));
    CHECK(time_status_is_fine(time_status::finebackupsteering));
    CHECK(time_status_is_fine(time_status::finesteering));
    CHECK(time_status_is_fine(time_status::sattime));
    CHECK_FALSE(time_status_is_fine(time_status::fineadjusting));
    CHECK_FALSE(time_status_is_fine(time_status::coarsesteering));
    CHECK_FALSE(time_status_is_fine(time_status::unknown));
    CHECK_FALSE(time_status_is_fine(kUnknownEnum));
}

TEST_CASE("ClockOffsetTracker: smooths host-receiver offset, re-seeds on a step")
{
    ClockOffsetTracker c;
    CHECK_FALSE(c.valid());
    c.update(1'000'050'000, 1'000'000'000);
    CHECK(c.valid());
    CHECK(c.last_us() == 50'000);
    CHECK(c.smoothed_us() == 50'000);
    c.update(2'000'066'000, 2'000'000'000);  // 66 ms: moves 1/16 of the way
    CHECK(c.last_us() == 66'000);
    CHECK(c.smoothed_us() == 51'000);
    c.update(3'005'000'000, 3'000'000'000);  // the host clock stepped 5 s
    CHECK(c.smoothed_us() == 5'000'000);
    CHECK(c.jumps() == 1);
    CHECK(c.samples() == 3);
}
