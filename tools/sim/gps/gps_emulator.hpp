// A NovAtel OEM4-class receiver (or its NMEA output) without any I/O: host command bytes in,
// receiver bytes out, driven by the caller's clock. gps_command.cpp puts it on a pty.
//
// It answers UNLOGALL, LOG <msg> [ONTIME <period>] and COM <baud> with "<OK" (and a port
// prompt) and unknown commands or messages with "<ERROR:...", and emits the logged
// messages on time-of-week multiples of their period from a trajectory (stationary, or a
// straight line at constant speed), with position noise, a scripted sequence of position
// types (e.g. SINGLE -> PSRDIFF -> NARROW_INT) and faults (garbage bursts, silence, bit
// errors per byte, truncated frames).
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "position_error.hpp"
#include "ugv/novatel/messages.hpp"

namespace ugv::sim::gps {

enum class Protocol { novatel, nmea };

struct ScriptStep
{
    double at_s = 0;            // seconds after start
    uint32_t position_type = 16;
};

// The antenna's true motion at a time (ugv-sim world): position and Doppler velocity.
struct AntennaTruth
{
    double latitude_deg = 0, longitude_deg = 0;
    double height_msl_m = 0;
    double horizontal_speed_mps = 0;
    double track_deg = 0;            // clockwise from true north
    double vertical_speed_mps = 0;
};
using Trajectory = std::function<AntennaTruth(int64_t utime)>;

struct EmulatorConfig
{
    Protocol protocol = Protocol::novatel;
    int baud = 9600;                  // the receiver port's rate at power-up
    double latitude_deg = 50.0;       // start of the trajectory
    double longitude_deg = -110.7;
    double height_msl_m = 750.0;
    double undulation_m = -17.0;
    double speed_mps = 0.0;           // 0: stationary
    double heading_deg = 0.0;         // clockwise from north
    Trajectory trajectory;            // when set, replaces the start point, speed and heading
    double noise_scale = 1.0;         // x the position type's sigma; 0 = exact
    // Set: the position error is this Gauss-Markov model's (its sigmas x noise_scale, also
    // reported); unset: white noise of sigma_of(type) x noise_scale, sigma_of reported.
    std::optional<PositionErrorConfig> markov;
    uint32_t seed = 1;
    int leap_seconds = 18;
    std::vector<ScriptStep> script{{0.0, 16}};
    bool preconfigured = false;       // logs already running at power-up (passive hosts)
    double rate_hz = 4.0;             // of the preconfigured logs
    double garbage_period_s = 0;      // > 0: a burst of random bytes this often
    double silence_at_s = -1;         // >= 0: stop output for silence_for_s from then
    double silence_for_s = 0;
    double bit_error_rate = 0;        // per byte sent (logs and replies): one bit flipped
    double truncate_probability = 0;  // per log frame: only its first 1..size-1 bytes are sent
};

class GpsEmulator
{
public:
    GpsEmulator(EmulatorConfig config, int64_t start_utime);

    // Bytes the host wrote (at the right baud). Returns the receiver's replies.
    std::string on_host_bytes(const uint8_t* data, std::size_t n);
    // Everything due up to now_utime (logs, garbage). Call often (every few ms).
    std::string tick(int64_t now_utime);

    int baud() const { return baud_; }
    std::size_t active_logs() const { return logs_.size(); }
    uint32_t position_type_at(double elapsed_s) const;
    // Truth of the trajectory (no noise) at a time.
    void truth(int64_t utime, double& latitude_deg, double& longitude_deg) const;
    uint64_t commands_received() const { return commands_; }
    uint64_t bytes_damaged() const { return bytes_damaged_; }
    uint64_t frames_truncated() const { return frames_truncated_; }
    // NMEA sentences the bit errors changed while their checksum still holds: the host cannot
    // tell them from good ones (tests allow that many wrong fixes, and no more).
    uint64_t nmea_damage_unseen() const { return nmea_damage_unseen_; }

private:
    struct ActiveLog
    {
        std::string message;       // upper case, e.g. "BESTPOSB"
        int64_t period_us;
        int64_t next_utime;
    };

    std::string execute(const std::string& line);
    void add_log(const std::string& message, double period_s, int64_t now_utime);
    std::string emit(const std::string& message, int64_t utime);
    novatel::Position position_at(int64_t utime);
    novatel::Velocity velocity_at(int64_t utime);

    EmulatorConfig config_;
    int64_t start_utime_;
    int64_t now_utime_;
    int baud_;
    std::vector<ActiveLog> logs_;
    std::string line_;             // a command being received
    std::mt19937 rng_;
    std::optional<PositionErrorModel> markov_;
    int64_t next_garbage_utime_ = 0;
    uint64_t commands_ = 0;
    uint64_t bytes_damaged_ = 0;
    uint64_t frames_truncated_ = 0;
    uint64_t nmea_damage_unseen_ = 0;
};

// Of the NMEA sentences in `sent`, how many arrive as `received` (same length, some bits
// flipped) changed but with a checksum that still holds.
uint64_t count_nmea_damage_unseen(const std::string& sent, const std::string& received);

// "SINGLE@0,PSRDIFF@5,NARROW_INT@10" -> steps; throws std::invalid_argument on a bad item.
std::vector<ScriptStep> parse_script(const std::string& text);
// The GGA quality a position type is reported as.
int gga_quality_of(uint32_t position_type);
// 1-sigma horizontal position error of a position type (m).
double sigma_of(uint32_t position_type);

}  // namespace ugv::sim::gps
