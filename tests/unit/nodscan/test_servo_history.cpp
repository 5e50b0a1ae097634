#include <catch2/catch.hpp>

#include <cmath>

#include "ugv/nodscan/servo_history.hpp"

using namespace ugv::nodscan;
using Catch::Detail::Approx;

TEST_CASE("Servo history interpolates between bracketing samples")
{
    ServoHistory h;
    CHECK_FALSE(h.angle_at(0));
    h.add({1'000'000, 0.0});
    h.add({1'010'000, 0.1});
    h.add({1'020'000, 0.3});
    CHECK(*h.angle_at(1'000'000) == Approx(0.0));
    CHECK(*h.angle_at(1'005'000) == Approx(0.05));
    CHECK(*h.angle_at(1'010'000) == Approx(0.1));
    CHECK(*h.angle_at(1'015'000) == Approx(0.2));
    CHECK(*h.angle_at(1'020'000) == Approx(0.3));
    CHECK_FALSE(h.angle_at(999'999));          // older than the history
    CHECK_FALSE(h.angle_at(1'020'001));        // newer, and no extrapolation allowed
    CHECK(*h.angle_at(1'025'000, 5'000) == Approx(0.4));  // extends the last segment
    CHECK_FALSE(h.angle_at(1'025'001, 5'000));
}

TEST_CASE("Servo history rejects samples out of order or not finite")
{
    ServoHistory h;
    CHECK(h.add({100, 0.0}));
    CHECK_FALSE(h.add({100, 0.1}));
    CHECK_FALSE(h.add({50, 0.1}));
    CHECK_FALSE(h.add({200, NAN}));
    CHECK(h.rejected() == 3);
    CHECK(h.size() == 1);
}

TEST_CASE("Servo history forgets samples older than its window")
{
    ServoHistory h(100'000);
    for (int64_t t = 0; t <= 1'000'000; t += 10'000) h.add({t, 0.0});
    CHECK(h.oldest_utime() == 900'000);
    CHECK(h.newest_utime() == 1'000'000);
}

TEST_CASE("Batch evaluation equals one-by-one evaluation")
{
    ServoHistory h;
    for (int k = 0; k < 50; ++k) h.add({k * 10'000 + (k % 3) * 1'000, std::sin(k * 0.1)});
    double a[100];
    uint8_t ok[100];
    const auto n = h.angles_at(5'000, 4'900.0, 100, 2'000, a, ok);
    std::size_t count = 0;
    for (std::size_t i = 0; i < 100; ++i) {
        const auto single = h.angle_at(5'000 + static_cast<int64_t>(4'900.0 * static_cast<double>(i)), 2'000);
        REQUIRE(static_cast<bool>(ok[i]) == single.has_value());
        if (single) {
            CHECK(a[i] == Approx(*single));
            ++count;
        }
    }
    CHECK(n == count);
    CHECK(count == 100);  // 5 ms .. 490.1 ms, samples up to 491 ms
}
