#include <catch2/catch.hpp>

#include <numbers>

#include "ugv/canopen/units.hpp"

using ugv::canopen::UnitConversion;
using Catch::Detail::Approx;

TEST_CASE("Counts <-> radians with gear ratio, zero offset and direction")
{
    UnitConversion u{4096.0, 100.0, 1000, -1};  // 409600 counts per output turn
    CHECK(u.to_rad(1000) == 0.0);
    CHECK(u.to_rad(1000 + 102400) == Approx(-std::numbers::pi / 2).epsilon(1e-12));
    CHECK(u.to_counts(-std::numbers::pi / 2) == 1000 + 102400);
    CHECK(u.to_counts(std::numbers::pi / 2) == 1000 - 102400);
    CHECK(u.to_counts(u.to_rad(123456)) == 123456);
    CHECK(u.to_rad_s(409600.0) == Approx(-2 * std::numbers::pi));
    CHECK(u.to_counts_rate(-2 * std::numbers::pi) == 409600u);
    // One count is the resolution: 2 pi / 409600 rad.
    CHECK(u.to_counts(-1.4 * 2 * std::numbers::pi / 409600) == 1001);
}

TEST_CASE("Counts saturate at the int32 range instead of wrapping")
{
    UnitConversion u{4096.0, 1000.0, 0, 1};
    CHECK(u.to_counts(1e9) == INT32_MAX);
    CHECK(u.to_counts(-1e9) == INT32_MIN);
}
