#include "ugv/sick_lms2xx/timing.hpp"

#include <cmath>

namespace ugv::sick_lms2xx {

int sweeps_per_scan(int resolution_cdeg)
{
    if (resolution_cdeg <= 25) return 4;
    if (resolution_cdeg <= 50) return 2;
    return 1;
}

double scan_period_s(int resolution_cdeg) { return sweeps_per_scan(resolution_cdeg) / kMirrorHz; }

int beams_per_scan(int angle_deg, int resolution_cdeg) { return angle_deg * 100 / resolution_cdeg + 1; }

double line_time_s(std::size_t n, int baud) { return baud > 0 ? static_cast<double>(n) * 10.0 / baud : 0.0; }

ScanStamp stamp_scan(int64_t arrival_utime, std::size_t telegram_bytes, int baud, double scan_duration_s, int nbeams)
{
    ScanStamp s;
    const double back_s = line_time_s(telegram_bytes, baud) + scan_duration_s;
    s.first_beam_utime = arrival_utime - static_cast<int64_t>(std::llround(back_s * 1e6));
    s.time_increment_s = nbeams > 1 ? scan_duration_s / (nbeams - 1) : 0.0;
    return s;
}

}  // namespace ugv::sick_lms2xx
