// Decoded logs/sentences -> fixes and velocities with a measurement time stamp. Pure: the
// daemon turns these plain structs into gps_fix_t / gps_velocity_t.
//
// Time: utime is the measurement time. When the receiver's clock is FINE or better (binary
// and ASCII logs carry the time status; for NMEA, a fix implies it), it is the receiver's
// GPS time converted to UTC with the configured leap seconds. Otherwise it is the frame's
// arrival time minus its transmission time and the configured output latency.
//
// Sources: a receiver may send the same epoch as BESTPOS, PSRPOS and GGA at once. The best
// one seen recently wins (the ranks in log_table.hpp: BESTPOS > PSRPOS > GGA; BESTVEL >
// PSRVEL > RMC > VTG); a lower one is used only when no better one arrived within
// source_hold_us.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "ugv/novatel/fix_quality.hpp"
#include "ugv/novatel/gps_time.hpp"
#include "ugv/novatel/log_table.hpp"
#include "ugv/novatel/messages.hpp"

namespace ugv::novatel {

// Same numbering as gps_fix_t.SOURCE_*.
enum class Source : int8_t { novatel_binary = 0, novatel_ascii = 1, nmea = 2 };

struct Fix
{
    int64_t utime = 0;
    bool time_from_receiver = false;
    int32_t gps_week = -1;
    int32_t gps_ms = -1;
    double latitude_deg = kNaN;
    double longitude_deg = kNaN;
    double height_m = kNaN;           // ellipsoidal = MSL height + undulation
    double undulation_m = kNaN;
    double sigma_latitude_m = kNaN;
    double sigma_longitude_m = kNaN;
    double sigma_height_m = kNaN;
    int32_t solution_status = -1;     // raw receiver enums (-1: unknown name / not given)
    int32_t position_type = -1;       // or the GGA quality for NMEA
    FixQuality quality = FixQuality::none;
    int satellites_used = -1;
    int satellites_tracked = -1;
    double differential_age_s = kNaN; // NaN unless differential
    Source source = Source::novatel_binary;
};

struct VelocityFix
{
    int64_t utime = 0;                // already corrected by the receiver's latency
    bool time_from_receiver = false;
    double horizontal_speed_mps = kNaN;
    double track_rad = kNaN;          // clockwise from true north
    double vertical_speed_mps = kNaN;
    double latency_s = kNaN;
    int32_t solution_status = -1;
    int32_t velocity_type = -1;
    Source source = Source::novatel_binary;
};

struct InterpreterConfig
{
    int leap_seconds = kDefaultLeapSeconds;
    int64_t output_latency_us = 0;    // receiver: measurement to first byte out (fallback time)
    int baud = 0;                     // for the frame's own transmission time (0 = ignore)
    int64_t source_hold_us = 2'000'000;
};

struct Interpretation
{
    std::optional<Fix> fix;
    std::optional<VelocityFix> velocity;
};

class Interpreter
{
public:
    explicit Interpreter(InterpreterConfig config = {}) : config_(config) {}
    void set_baud(int baud) { config_.baud = baud; }

    // One decoded message (arrival_utime: its last byte's arrival; frame_bytes: its size).
    Interpretation on_message(const Message& message, FrameKind kind, int64_t arrival_utime,
                              std::size_t frame_bytes);

    const ClockOffsetTracker& clock() const { return clock_; }
    // The host clock's offset from GPS time: the frame's arrival less its transmission time
    // and output_latency (what the arrival fallback would stamp) minus the receiver's time;
    // updated while the receiver's time is FINE. Output latency not configured stays in it.
    const ClockOffsetTracker& host_clock() const { return host_clock_; }
    // The receiver's last time status (binary/ASCII logs), time_status::unknown before any.
    uint32_t last_time_status() const { return last_time_status_; }
    uint64_t superseded() const { return superseded_; }  // messages dropped for a better source

private:
    int64_t fallback_utime(int64_t arrival_utime, std::size_t frame_bytes) const;
    using SourceTimes = std::array<int64_t, kSourceRanks>;  // last arrival by source rank, 0 = never
    bool accept(int rank, int64_t arrival_utime, SourceTimes& last_seen);
    Fix fix_from_position(const Position& p, FrameKind kind, int64_t arrival, std::size_t bytes);
    VelocityFix velocity_from_log(const Velocity& v, FrameKind kind, int64_t arrival, std::size_t bytes);
    Fix fix_from_gga(const Gga& g, int64_t arrival, std::size_t bytes);
    void attach_gst(Fix& fix, const Gst& gst) const;
    Interpretation on_gga(const Gga& g, int64_t arrival, std::size_t bytes);
    Interpretation on_gst(const Gst& g);
    Interpretation on_nmea_velocity(double utc_s, bool fix_valid, double speed_mps, double track_deg,
                                    int rank, int64_t arrival, std::size_t bytes);

    InterpreterConfig config_;
    ClockOffsetTracker clock_;
    ClockOffsetTracker host_clock_;
    uint32_t last_time_status_ = 20;
    uint64_t superseded_ = 0;
    SourceTimes position_seen_{};
    SourceTimes velocity_seen_{};
    // NMEA: a GGA waits for the GST of the same epoch once GSTs have been seen.
    std::optional<Fix> pending_gga_;
    double pending_gga_utc_s_ = kNaN;
    std::optional<Gst> last_gst_;
    bool gst_seen_ = false;
};

}  // namespace ugv::novatel
