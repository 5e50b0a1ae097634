// Word scalings, per-unit gains, the timer tick from the EEPROM timing words.
#include <catch2/catch.hpp>

#include "ugv/microstrain_gx1/scaling.hpp"

using namespace ugv::microstrain_gx1;

namespace {
Frame frame_of(uint8_t command, const std::vector<uint16_t>& words)
{
    FrameParser p;
    const auto bytes = encode_reply(command, words);
    p.feed(bytes.data(), bytes.size());
    Frame f;
    REQUIRE(p.next(f));
    return f;
}
constexpr double pi = 3.14159265358979323846;
}  // namespace

TEST_CASE("timer tick from the EEPROM timing words", "[gx1][scaling]")
{
    CHECK(TimingWords{}.tick_period_s() == Approx(6.5536e-3).epsilon(1e-12));
    CHECK(TimingWords{{4, 10, 250, 10}}.tick_period_s() == Approx(10e-3).epsilon(1e-12));
    CHECK(TimingWords{{16, 0, 256, 1}}.tick_period_s() == 0.0);
}

TEST_CASE("Euler, unit and temperature word scalings", "[gx1][scaling]")
{
    CHECK(euler_rad(16384) == Approx(pi / 2));       // 16384 * 360/65536 = 90 deg
    CHECK(euler_rad(-8192) == Approx(-pi / 4));
    CHECK(euler_raw(pi / 2) == 16384);
    CHECK(euler_raw(-pi / 4) == -8192);
    CHECK(euler_raw(3 * pi / 2) == -16384);           // wrapped into one turn
    CHECK(unit_value(8192) == 1.0);
    CHECK(unit_value(-4096) == -0.5);
    CHECK(unit_raw(0.5) == 4096);
    CHECK(unit_raw(5.0) == 32767);                    // saturates
    // (raw * 5/65536 - 0.5) * 100: raw 13107 -> 0.99998 V -> 49.998 C
    CHECK(temperature_c(13107) == Approx((13107 * 5.0 / 65536.0 - 0.5) * 100.0));
    CHECK(temperature_c(6554) == Approx(0.003052).margin(1e-5));  // (0.50003052 - 0.5) * 100
}

TEST_CASE("vectors scale with the unit's own GainScale", "[gx1][scaling]")
{
    // raw / (32768000 / GainScale): accel gain 8500, raw 3855 -> 1.0000 g.
    CHECK(vector_value(3855, 8500.0) == Approx(3855 * 8500.0 / 32768000.0));
    CHECK(vector_value(3855, 8500.0) == Approx(1.0).epsilon(1e-4));
    // A different unit's gain gives a different value for the same word.
    CHECK(vector_value(3855, 7000.0) == Approx(0.8235).epsilon(1e-3));
    CHECK(vector_raw(1.0, 8500.0) == 3855);
    CHECK(vector_raw(-0.5, 10000.0) == -1638);
}

TEST_CASE("decode 0x31: Euler, accel in m/s^2, rate, ticks", "[gx1][scaling]")
{
    GainScales g{.gyro = 10000, .accel = 8500, .mag = 2000};
    const Frame f = frame_of(0x31, {static_cast<uint16_t>(1820), static_cast<uint16_t>(-910), 16384,  // 10, -5, 90 deg
                                    0, 0, static_cast<uint16_t>(-3855), 3277, 0, 0, 4242});
    const DeviceSample s = decode_sample(f, g);
    CHECK(s.has_euler);
    CHECK(s.has_accel);
    CHECK(s.has_rate);
    CHECK_FALSE(s.has_mag);
    CHECK_FALSE(s.has_quaternion);
    CHECK(s.roll_rad == Approx(1820 * 2 * pi / 65536));
    CHECK(s.pitch_rad == Approx(-910 * 2 * pi / 65536));
    CHECK(s.yaw_rad == Approx(pi / 2));
    CHECK(s.accel_mps2[2] == Approx(-3855 * 8500.0 / 32768000.0 * 9.80665));
    CHECK(s.rate_radps[0] == Approx(3277 * 10000.0 / 32768000.0));
    CHECK(s.ticks == 4242);
    CHECK(s.has_ticks);
}

TEST_CASE("decode 0x0C: quaternion and all three vectors", "[gx1][scaling]")
{
    GainScales g{.gyro = 12000, .accel = 8000, .mag = 2500};
    std::vector<uint16_t> w = {8192, 0, 0, 0, 100, 200, 300, 400, 500, 600, 700, 800, 900, 77};
    const DeviceSample s = decode_sample(frame_of(0x0C, w), g);
    CHECK(s.has_quaternion);
    CHECK(s.has_mag);
    CHECK(s.quaternion[0] == 1.0);
    CHECK(s.mag_gauss[0] == Approx(100 * 2500.0 / 32768000.0));
    CHECK(s.accel_mps2[0] == Approx(400 * 8000.0 / 32768000.0 * 9.80665));
    CHECK(s.rate_radps[2] == Approx(900 * 12000.0 / 32768000.0));
    CHECK(s.ticks == 77);
}

TEST_CASE("decode the other data replies", "[gx1][scaling]")
{
    const GainScales g;
    auto t = decode_sample(frame_of(0x07, {13107, 5}), g);
    CHECK(t.has_temperature);
    CHECK(t.temperature_c == Approx(temperature_c(13107)));
    auto m = decode_sample(frame_of(0x0B, {8192, 0, 0, 0, 8192, 0, 0, 0, 8192, 9}), g);
    CHECK(m.has_matrix);
    CHECK(m.matrix[4] == 1.0);
    CHECK(m.ticks == 9);
    auto r = decode_sample(frame_of(0x01, {1, 2, 3, 4, 5, 6, 7, 8, 65535, 10}), g);
    CHECK(r.has_raw);
    CHECK(r.raw_bits[8] == 65535);
    auto e = decode_sample(frame_of(0x0E, {0, 0, static_cast<uint16_t>(-16384), 3}), g);
    CHECK(e.yaw_rad == Approx(-pi / 2));
    auto v = decode_sample(frame_of(0x02, {0, 0, 0, 0, 0, 3855, 0, 0, 0, 1}), g);
    CHECK(v.accel_mps2[2] == Approx(3855 * 8500.0 / 32768000.0 * 9.80665));
    auto fw = decode_sample(frame_of(0xF0, {0x0302}), g);
    CHECK_FALSE(fw.has_ticks);
}
