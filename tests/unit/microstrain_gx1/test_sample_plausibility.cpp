// The plausibility check behind the GX1's weak checksum: one damaged sample among good ones is
// dropped and counted, a real change is taken after one sample, the timer word is checked too.
#include <catch2/catch.hpp>

#include <cmath>

#include "ugv/microstrain_gx1/sample_plausibility.hpp"

using ugv::microstrain_gx1::DeviceSample;
using ugv::microstrain_gx1::SamplePlausibility;

namespace {

constexpr double kTick = 6.5536e-3;  // default timing: a frame every 3 ticks is ~51 Hz
constexpr double kDeg = 3.14159265358979323846 / 180.0;

// A unit turning at 20 deg/s in yaw, level, gravity on z, at frame k.
DeviceSample at(int k)
{
    DeviceSample s;
    s.has_euler = s.has_rate = s.has_accel = s.has_ticks = true;
    s.ticks = static_cast<uint16_t>(65000 + 3 * k);  // wraps at k = 179
    s.yaw_rad = std::remainder(170 * kDeg + 20 * kDeg * 3 * kTick * k, 2 * 3.14159265358979323846);
    s.rate_radps = {0.0, 0.0, 20 * kDeg};
    s.accel_mps2 = {0.0, 0.0, -9.80665};
    return s;
}

}  // namespace

TEST_CASE("Consecutive samples of a turning unit pass, across the yaw and timer wraps")
{
    SamplePlausibility p;
    CHECK_FALSE(p.check(at(0), kTick));  // the first waits for the second
    for (int k = 1; k < 400; ++k) CHECK(p.check(at(k), kTick));
    CHECK(p.implausible() == 0);
}

TEST_CASE("One damaged sample is dropped and counted; its neighbours pass")
{
    SamplePlausibility p;
    for (int k = 0; k < 10; ++k) p.check(at(k), kTick);
    DeviceSample roll = at(10);
    roll.roll_rad = 55 * kDeg;  // what a cancelling pair of flips once put on the bus
    CHECK_FALSE(p.check(roll, kTick));
    CHECK(p.check(at(11), kTick));
    CHECK(p.implausible() == 1);

    DeviceSample accel = at(12);
    accel.accel_mps2[2] = 30.0;
    CHECK_FALSE(p.check(accel, kTick));
    CHECK(p.check(at(13), kTick));
    DeviceSample timer = at(14);
    timer.ticks = static_cast<uint16_t>(timer.ticks + 0x4000);  // a damaged timer word: 107 s ahead
    CHECK_FALSE(p.check(timer, kTick));
    CHECK(p.check(at(15), kTick));
    DeviceSample rate = at(16);
    rate.rate_radps[0] = 4.0;
    CHECK_FALSE(p.check(rate, kTick));
    CHECK(p.check(at(17), kTick));
    CHECK(p.implausible() == 4);
}

TEST_CASE("A real change (two samples that agree with each other) is taken after one")
{
    SamplePlausibility p;
    for (int k = 0; k < 10; ++k) p.check(at(k), kTick);
    // The unit restarted its filter: the attitude jumps 30 deg and stays.
    DeviceSample a = at(10), b = at(11), c = at(12);
    for (DeviceSample* s : {&a, &b, &c}) s->pitch_rad = 30 * kDeg;
    CHECK_FALSE(p.check(a, kTick));
    CHECK(p.check(b, kTick));
    CHECK(p.check(c, kTick));
    CHECK(p.implausible() == 0);
}

TEST_CASE("Lost frames in between widen the bounds with the time the timer says passed")
{
    SamplePlausibility p;
    for (int k = 0; k < 10; ++k) p.check(at(k), kTick);
    CHECK(p.check(at(40), kTick));  // 30 frames (0.6 s, 12 deg of yaw) later
    CHECK(p.implausible() == 0);
}
