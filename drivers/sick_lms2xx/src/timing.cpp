#include "ugv/sick_lms2xx/timing.hpp"

#include <cmath>
#include <stdexcept>

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

int SweepOrder::sweep_of_beam(int i) const
{
    const int phase = i % sweeps;
    for (int k = 0; k < sweeps; ++k)
        if (order[static_cast<std::size_t>(k)] == phase) return k;
    return 0;
}

bool SweepOrder::operator==(const SweepOrder& o) const
{
    if (sweeps != o.sweeps) return false;
    for (int k = 0; k < sweeps; ++k)
        if (order[static_cast<std::size_t>(k)] != o.order[static_cast<std::size_t>(k)]) return false;
    return true;
}

SweepOrder natural_order(int resolution_cdeg)
{
    SweepOrder o;
    o.sweeps = sweeps_per_scan(resolution_cdeg);
    return o;
}

SweepOrder parse_sweep_order(const std::string& text, int resolution_cdeg)
{
    SweepOrder o = natural_order(resolution_cdeg);
    if (text.empty()) return o;
    const std::string example = o.sweeps == 4 ? "\"0123\" or \"1032\"" : o.sweeps == 2 ? "\"01\" or \"10\"" : "\"0\"";
    const std::string res = o.sweeps == 4 ? "0.25" : o.sweeps == 2 ? "0.5" : "1";
    if (static_cast<int>(text.size()) != o.sweeps)
        throw std::invalid_argument("\"" + text + "\" has " + std::to_string(text.size()) + " digits; a " + res +
                                    " deg scan has " + std::to_string(o.sweeps) + " sweeps (e.g. " + example + ")");
    unsigned seen = 0;
    for (int k = 0; k < o.sweeps; ++k) {
        const int d = text[static_cast<std::size_t>(k)] - '0';
        if (d < 0 || d >= o.sweeps || (seen & (1u << d)) != 0)
            throw std::invalid_argument("\"" + text + "\" is not an order of the beam phases 0.." +
                                        std::to_string(o.sweeps - 1) + ", each once (e.g. " + example + ")");
        seen |= 1u << d;
        o.order[static_cast<std::size_t>(k)] = static_cast<int8_t>(d);
    }
    return o;
}

std::string to_string(const SweepOrder& o)
{
    std::string s;
    for (int k = 0; k < o.sweeps; ++k) s += static_cast<char>('0' + o.order[static_cast<std::size_t>(k)]);
    return s;
}

double ScanStamp::beam_offset_s(int i) const { return order.sweep_of_beam(i) * sweep_period_s + i * time_increment_s; }

ScanStamp stamp_scan(int64_t end_utime, int angle_deg, int resolution_cdeg, BeamTiming timing,
                     const SweepOrder& order)
{
    const double turn_s = 1.0 / kMirrorHz;
    const int sweeps = sweeps_per_scan(resolution_cdeg);
    const int n = beams_per_scan(angle_deg, resolution_cdeg);
    ScanStamp s;
    double back_s = 0.0;
    if (timing == BeamTiming::linear) {
        back_s = sweeps * turn_s;
        s.time_increment_s = n > 1 ? back_s / (n - 1) : 0.0;
        s.sweep_period_s = back_s;
        s.order = SweepOrder{};
    } else {
        back_s = (sweeps - 1) * turn_s + angle_deg * turn_s / 360.0;
        s.time_increment_s = resolution_cdeg / 100.0 * turn_s / 360.0;
        s.sweep_period_s = turn_s;
        s.order = order.sweeps == sweeps ? order : natural_order(resolution_cdeg);
    }
    s.first_beam_utime = end_utime - static_cast<int64_t>(std::llround(back_s * 1e6));
    return s;
}

int64_t scan_end_utime(int64_t arrival_utime, std::size_t telegram_bytes, int baud)
{
    return arrival_utime - static_cast<int64_t>(std::llround(line_time_s(telegram_bytes, baud) * 1e6));
}

}  // namespace ugv::sick_lms2xx
