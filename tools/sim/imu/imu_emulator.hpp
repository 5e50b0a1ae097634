// A MicroStrain 3DM-GX1 as seen from its serial line, without any I/O: bytes from the host go
// in with receive(), bytes the unit sends come out of output(). Time is passed in (seconds
// of host time), so tests drive it deterministically; the pty runner passes the wall clock.
//
// It answers every command of the fact sheet (data replies from the attitude callback plus
// noise, EEPROM reads and writes, gains, identity, tare, gyro bias, temperature), streams in
// continuous mode on its own timer (ticks from the EEPROM timing words, a clock error in
// ppm), and can be told to misbehave (garbage bytes, silence, streamed frames cut short).
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <vector>

#include <Eigen/Core>

#include "ahrs_model.hpp"
#include "ugv/microstrain_gx1/scaling.hpp"

namespace ugv::sim::imu {


// Level, constant heading.
AttitudeFn fixed_attitude(double roll_rad, double pitch_rad, double yaw_rad);
// Level, heading turning at a constant rate (clockwise positive, NED) from yaw0.
AttitudeFn slow_yaw(double yaw0_rad, double yaw_rate_radps);
// What a person does at tests/bench/imu-signs.sh's prompts, in a loop from t0_s (20 s a
// cycle, the unit's NED convention): level 3 s; roll right side down to 30 deg in 1 s and
// back in 1 s; level 3 s; nose up to 20 deg and back, 1 s each; level 3 s; turn left
// (counter-clockwise seen from above) by 90 deg in 2 s and back in 2 s; level 3 s. One axis
// at a time from level, so the sensor rates are the Euler rates.
AttitudeFn bench_motions(double t0_s, double yaw0_rad);

struct NoiseModel
{
    double angle_sigma_rad = 0;
    double accel_sigma_mps2 = 0;
    double rate_sigma_radps = 0;
    unsigned seed = 1;
};

struct EmulatorConfig
{
    uint16_t firmware_version = 0x0312;
    uint16_t serial_number = 2207;
    uint16_t gyro_gain_scale = 10000;   // EEPROM 130
    uint16_t accel_gain_scale = 8500;   // EEPROM 230
    uint16_t mag_gain_scale = 2000;     // EEPROM 232
    microstrain_gx1::TimingWords timing;
    double rate_hz = 50.0;              // continuous output, rounded to whole timer ticks
    double clock_ppm = 0.0;             // the unit's timer runs this much fast
    bool streaming_at_power_on = false; // left streaming by a previous user
    uint8_t power_on_command = 0x31;
    uint16_t timer_at_power_on = 0;     // u16 timer value at power-on (to test the wrap)
    NoiseModel noise;
    // The true motion. With ahrs set, the attitude the unit reports is its filter's (error
    // model "ahrs": false tilt under acceleration, gyro bias, disturbed heading; the rates
    // carry the same bias); without, the truth. White noise is added on top either way.
    AttitudeFn attitude = fixed_attitude(0, 0, 0);
    std::optional<AhrsConfig> ahrs;
    double ahrs_start_s = -1;  // the filter's grid origin (< 0: power-on)
    Eigen::Vector3d mag_field_ned_gauss{0.2, 0.0, 0.45};
    double temperature_c = 25.0;
};

struct EmulatorCounters
{
    uint64_t commands = 0;       // complete commands understood
    uint64_t ignored_bytes = 0;  // bytes that start no command
    uint64_t frames_streamed = 0;
    uint64_t frames_truncated = 0;  // streamed frames cut short (set_truncate_every)
    uint64_t replies_truncated = 0;  // command replies cut short (set_truncate_replies)
};

class Gx1Emulator
{
public:
    explicit Gx1Emulator(EmulatorConfig config, double power_on_s = 0.0);

    // Bytes from the host at time t_s (commands may arrive split over calls).
    void receive(const uint8_t* data, std::size_t n, double t_s);
    // Produces the continuous-mode frames due up to t_s.
    void advance(double t_s);
    // Bytes waiting to go to the host, in order.
    std::deque<uint8_t>& output() { return out_; }
    // Host time of the next continuous frame (infinity when not streaming).
    double next_frame_s() const;

    // Fault injection.
    void inject_garbage(std::size_t n);  // random bytes, rich in command bytes
    void set_silent(bool silent) { silent_ = silent; }  // produce nothing (a hung unit)
    // Every n-th streamed frame goes out cut short: only its first k bytes (k random in
    // 1 .. length-1), then the next frame follows as usual. 0 = never.
    void set_truncate_every(unsigned n) { truncate_every_ = n; }
    // The next n replies to commands (the handshake's) go out cut short the same way.
    void set_truncate_replies(unsigned n) { truncate_replies_ = n; }

    bool streaming() const { return streaming_; }
    uint8_t streamed_command() const { return stream_command_; }
    uint16_t eeprom(uint16_t address) const;
    double tick_period_s() const;
    uint16_t ticks_at(double t_s) const;
    // A data reply (any data command) for time t_s: used by polling and continuous mode.
    std::vector<uint8_t> data_reply(uint8_t command, double t_s);
    const EmulatorCounters& counters() const { return counters_; }

private:
    void execute(const std::vector<uint8_t>& command, double t_s);
    void send(const std::vector<uint8_t>& bytes);
    void send_reply(std::vector<uint8_t> bytes);  // send(), unless set_truncate_replies cuts it
    void start_stream(uint8_t command, double t_s);
    int64_t device_ticks_at(double t_s) const;  // unwrapped
    std::vector<uint8_t> build_data_reply(uint8_t command, double t_s, uint16_t ticks);
    double noise(double sigma) { return sigma > 0 ? sigma * gauss_(rng_) : 0.0; }
    double host_time_of_tick(int64_t tick) const;

    EmulatorConfig config_;
    double power_on_s_;
    std::map<uint16_t, uint16_t> eeprom_;
    std::vector<uint8_t> pending_;  // a command waiting for its argument bytes
    std::array<uint16_t, 3> system_gains_{10, 10, 10};  // 0x24 / 0x25: accel, mag, bias
    std::deque<uint8_t> out_;
    bool streaming_ = false;
    bool silent_ = false;
    unsigned truncate_every_ = 0;
    unsigned truncate_replies_ = 0;
    uint8_t stream_command_ = 0;
    int64_t next_tick_ = 0;
    int64_t period_ticks_ = 1;
    std::mt19937 rng_;
    std::normal_distribution<double> gauss_{0.0, 1.0};
    EmulatorCounters counters_;
    std::unique_ptr<AhrsModel> ahrs_;
};

// Splits the output the way the real unit's USB-serial path does: random chunk sizes.
std::size_t random_chunk_size(std::mt19937& rng, std::size_t available);

}  // namespace ugv::sim::imu
