// Scan timing of the LMS 2xx and the time stamp model.
//
// The mirror turns at 75 Hz. At 1 deg a scan takes one sweep (13.33 ms); 0.5 deg interlaces
// two sweeps (26.67 ms) and 0.25 deg four (53.33 ms). The device sends a scan once it is
// complete, so the last beam was measured just before the telegram's first byte left the
// device, and the first one a scan duration earlier:
//   first_beam = arrival of the telegram's last byte - transmission time - scan duration
//   beam i     = first_beam + i * time_increment, time_increment = scan duration / (N - 1)
// With interlacing the true order of the beams is not monotonic in angle; this linear model
// is off by at most one sweep (13.3 ms) for an individual beam.
#pragma once

#include <cstddef>
#include <cstdint>

namespace ugv::sick_lms2xx {

inline constexpr double kMirrorHz = 75.0;

// Sweeps per complete scan for a resolution in 0.01 deg (100 -> 1, 50 -> 2, 25 -> 4).
int sweeps_per_scan(int resolution_cdeg);
// Seconds between complete scans.
double scan_period_s(int resolution_cdeg);
// Number of values in a complete scan (181 at 180/1, 361 at 180/0.5, 401 at 100/0.25).
int beams_per_scan(int angle_deg, int resolution_cdeg);
// Seconds to send n bytes at baud, 8N1 (10 bits per byte).
double line_time_s(std::size_t n, int baud);

struct ScanStamp
{
    int64_t first_beam_utime = 0;
    double time_increment_s = 0.0;
};
ScanStamp stamp_scan(int64_t arrival_utime, std::size_t telegram_bytes, int baud, double scan_duration_s, int nbeams);

}  // namespace ugv::sick_lms2xx
