// Scan timing of the LMS 2xx and the time stamp model.
//
// The mirror turns at 75 Hz (one sweep every 13.33 ms) and crosses the 180 deg field in half
// a turn. At 1 deg a scan is one sweep; at 0.5 deg two interlaced sweeps, at 0.25 deg four,
// each sweep measuring every S-th beam (S = sweeps per scan), so
//   beam i = scan start + sweep(i) * 13.33 ms + (i * resolution) * 13.33 ms / 360 deg
// where sweep(i) is the sweep that measured phase i mod S: `order[k]` is the phase measured
// by sweep k (a device fact, configured). The device sends a scan once it is complete, so
// its last sweep crossed the far edge of the field just before the telegram's first byte left:
//   last sweep's end = arrival of the telegram's last byte - transmission time
//   scan start       = last sweep's end - (S - 1) * 13.33 ms - field * 13.33 ms / 360 deg
// The linear model (kept for comparison) spreads the beams in angle order over the whole
// scan period: beam i = last beam - S * 13.33 ms + i * S * 13.33 ms / (N - 1); it is wrong
// by up to one sweep for a beam of an interlaced scan.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

namespace ugv::sick_lms2xx {

inline constexpr double kMirrorHz = 75.0;
inline constexpr int kMaxSweeps = 4;

// Sweeps per complete scan for a resolution in 0.01 deg (100 -> 1, 50 -> 2, 25 -> 4).
int sweeps_per_scan(int resolution_cdeg);
// Seconds between complete scans.
double scan_period_s(int resolution_cdeg);
// Number of values in a complete scan (181 at 180/1, 361 at 180/0.5, 401 at 100/0.25).
int beams_per_scan(int angle_deg, int resolution_cdeg);
// Seconds to send n bytes at baud, 8N1 (10 bits per byte).
double line_time_s(std::size_t n, int baud);

// Which beam phase each sweep measures: order[k] for sweep k (k < sweeps).
struct SweepOrder
{
    int sweeps = 1;
    std::array<int8_t, kMaxSweeps> order{0, 1, 2, 3};
    // The sweep that measures beam i.
    int sweep_of_beam(int i) const;
    bool operator==(const SweepOrder& o) const;
};
// The natural order (sweep k measures phase k) for a resolution.
SweepOrder natural_order(int resolution_cdeg);
// Parses "01", "10", "0123", "2031", ... (one digit per sweep, a permutation of 0..S-1 with
// S the sweeps of resolution_cdeg; "" = the natural order). Throws std::invalid_argument
// with a one-line reason.
SweepOrder parse_sweep_order(const std::string& text, int resolution_cdeg);
std::string to_string(const SweepOrder& o);

enum class BeamTiming { interlaced, linear };

// Each beam's time: beam i = first_beam_utime + sweep(i) * sweep_period_s + i * time_increment_s.
struct ScanStamp
{
    int64_t first_beam_utime = 0;  // start of the first sweep (at beam 0's angle)
    double time_increment_s = 0.0;
    double sweep_period_s = 0.0;
    SweepOrder order;              // sweeps = 1 for the linear model
    // Seconds from first_beam_utime to beam i.
    double beam_offset_s(int i) const;
};
// end_utime: the end of the scan's last sweep (the start of its telegram).
ScanStamp stamp_scan(int64_t end_utime, int angle_deg, int resolution_cdeg, BeamTiming timing,
                     const SweepOrder& order);
// The end of the last sweep of a telegram whose last byte arrived at arrival_utime.
int64_t scan_end_utime(int64_t arrival_utime, std::size_t telegram_bytes, int baud);

}  // namespace ugv::sick_lms2xx
