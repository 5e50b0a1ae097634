// Scaling of 3DM-GX1 reply words into physical values, in the DEVICE's convention (sensor
// axes X forward, Y right, Z down; Euler angles and quaternion relative to NED). The one
// conversion to the project's body FLU / world ENU is in orientation.hpp.
#pragma once

#include <array>
#include <cstdint>

#include "ugv/microstrain_gx1/frame_parser.hpp"

namespace ugv::microstrain_gx1 {

inline constexpr double standard_gravity_mps2 = 9.80665;

// Per-unit GainScale words from EEPROM (130 gyro, 230 accel, 232 mag). The defaults are the
// typical values, used only until the unit's own are read.
struct GainScales
{
    double gyro = 10000.0;
    double accel = 8500.0;
    double mag = 2000.0;
};

// The EEPROM timing words at 238, 240, 242, 246. The timer tick is their product times
// 100 ns: the defaults 16/16/256/1 give 6.5536 ms, 4/10/250/10 give 10 ms (fact sheet).
struct TimingWords
{
    std::array<uint16_t, 4> words{16, 16, 256, 1};
    // Seconds per timer tick; 0 when a word is 0 (invalid EEPROM content).
    double tick_period_s() const;
};

// One reply, scaled. Flags say which fields the command carries.
struct DeviceSample
{
    uint8_t command = 0;
    bool has_euler = false, has_quaternion = false, has_matrix = false;
    bool has_accel = false, has_rate = false, has_mag = false;
    bool has_temperature = false, has_raw = false, has_ticks = false;
    double roll_rad = 0, pitch_rad = 0, yaw_rad = 0;  // NED Euler (ZYX), yaw from magnetic north, clockwise
    std::array<double, 4> quaternion{1, 0, 0, 0};     // w, x, y, z: sensor -> NED
    std::array<double, 9> matrix{};                   // row-major orientation matrix M (NED -> sensor)
    std::array<double, 3> accel_mps2{};               // sensor axes, specific force
    std::array<double, 3> rate_radps{};               // sensor axes
    std::array<double, 3> mag_gauss{};                // sensor axes
    std::array<uint16_t, 9> raw_bits{};               // 0x01: mag, accel, rate A/D counts
    double temperature_c = 0;
    uint16_t ticks = 0;
};

// Word scalings of the fact sheet.
inline double euler_rad(int16_t raw) { return raw * (2.0 * 3.14159265358979323846 / 65536.0); }
inline double unit_value(int16_t raw) { return raw / 8192.0; }  // quaternion and matrix words
// raw / (32768000 / GainScale)
inline double vector_value(int16_t raw, double gain_scale) { return raw * gain_scale / 32768000.0; }
inline double temperature_c(uint16_t raw) { return (raw * 5.0 / 65536.0 - 0.5) * 100.0; }

// The inverse scalings (for the emulator and tests): nearest raw word, saturated.
int16_t euler_raw(double rad);
int16_t unit_raw(double value);
int16_t vector_raw(double value, double gain_scale);

// Decodes any data reply. Handshake-only replies (0x10, 0x28, ...) give a sample with only
// has_ticks set; callers read their words directly.
DeviceSample decode_sample(const Frame& frame, const GainScales& gains);

}  // namespace ugv::microstrain_gx1
