#include "ugv/microstrain_gx1/scaling.hpp"

#include <algorithm>
#include <cmath>

namespace ugv::microstrain_gx1 {

double TimingWords::tick_period_s() const
{
    double product = 1.0;
    for (uint16_t w : words) product *= w;
    return product * 100e-9;
}

static int16_t saturate(double v)
{
    return static_cast<int16_t>(std::clamp(std::lround(v), -32768L, 32767L));
}

int16_t euler_raw(double rad)
{
    // Wrap to [-pi, pi) first: the word covers one turn.
    const double two_pi = 2.0 * 3.14159265358979323846;
    const double wrapped = rad - two_pi * std::floor((rad + two_pi / 2) / two_pi);
    const long raw = std::lround(wrapped * 65536.0 / two_pi);
    return static_cast<int16_t>(static_cast<uint16_t>(raw & 0xFFFF));
}

int16_t unit_raw(double value) { return saturate(value * 8192.0); }
int16_t vector_raw(double value, double gain_scale) { return saturate(value * 32768000.0 / gain_scale); }

namespace {

void vectors_at(const Frame& f, std::size_t first, const GainScales& g, DeviceSample& s)
{
    for (std::size_t i = 0; i < 3; ++i) {
        s.mag_gauss[i] = vector_value(f.word_signed(first + i), g.mag);
        s.accel_mps2[i] = vector_value(f.word_signed(first + 3 + i), g.accel) * standard_gravity_mps2;
        s.rate_radps[i] = vector_value(f.word_signed(first + 6 + i), g.gyro);
    }
    s.has_mag = s.has_accel = s.has_rate = true;
}

void quaternion_at(const Frame& f, DeviceSample& s)
{
    for (std::size_t i = 0; i < 4; ++i) s.quaternion[i] = unit_value(f.word_signed(i));
    s.has_quaternion = true;
}

void euler_at(const Frame& f, DeviceSample& s)
{
    s.roll_rad = euler_rad(f.word_signed(0));
    s.pitch_rad = euler_rad(f.word_signed(1));
    s.yaw_rad = euler_rad(f.word_signed(2));
    s.has_euler = true;
}

}  // namespace

DeviceSample decode_sample(const Frame& f, const GainScales& g)
{
    DeviceSample s;
    s.command = f.command;
    s.has_ticks = reply_has_ticks(f.command);
    s.ticks = s.has_ticks ? f.ticks() : 0;
    switch (f.command) {
    case cmd::raw_sensor:
        for (std::size_t i = 0; i < 9; ++i) s.raw_bits[i] = f.words[i];
        s.has_raw = true;
        break;
    case cmd::stab_vectors:
    case cmd::inst_vectors: vectors_at(f, 0, g, s); break;
    case cmd::inst_quaternion:
    case cmd::stab_quaternion: quaternion_at(f, s); break;
    case cmd::temperature:
        s.temperature_c = temperature_c(f.words[0]);
        s.has_temperature = true;
        break;
    case cmd::inst_matrix:
    case cmd::stab_matrix:
        for (std::size_t i = 0; i < 9; ++i) s.matrix[i] = unit_value(f.word_signed(i));
        s.has_matrix = true;
        break;
    case cmd::stab_quaternion_vectors:
        quaternion_at(f, s);
        vectors_at(f, 4, g, s);
        break;
    case cmd::inst_euler:
    case cmd::stab_euler: euler_at(f, s); break;
    case cmd::stab_euler_accel_rate:
        euler_at(f, s);
        for (std::size_t i = 0; i < 3; ++i) {
            s.accel_mps2[i] = vector_value(f.word_signed(3 + i), g.accel) * standard_gravity_mps2;
            s.rate_radps[i] = vector_value(f.word_signed(6 + i), g.gyro);
        }
        s.has_accel = s.has_rate = true;
        break;
    default: break;
    }
    return s;
}

}  // namespace ugv::microstrain_gx1
