#include "ugv/logstat/scan_to_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace ugv::logstat {

void ScanToMapLatency::add_scan(int64_t recv_utime, int64_t last_beam_utime)
{
    pending_.push_back({recv_utime, last_beam_utime});
}

void ScanToMapLatency::add_map(int64_t recv_utime, int64_t map_utime)
{
    // Scans arrive in time order, so the covered ones are at the front; a scan received
    // after the map was published is not in it whatever its time.
    auto it = pending_.begin();
    while (it != pending_.end()) {
        if (it->last_beam_utime <= map_utime && it->recv_utime <= recv_utime) {
            // Exact in uint64; a difference beyond INT64_MAX (only in a hostile log) saturates.
            const uint64_t d = static_cast<uint64_t>(recv_utime) - static_cast<uint64_t>(it->recv_utime);
            latencies_.push_back(static_cast<int64_t>(std::min<uint64_t>(d, INT64_MAX)));
            it = pending_.erase(it);
        } else if (it->last_beam_utime > map_utime) {
            break;
        } else {
            ++it;
        }
    }
}

int64_t shifted_utime(int64_t utime, double offset_us)
{
    if (!std::isfinite(offset_us)) return utime;
    const double t = static_cast<double>(utime) + std::round(offset_us);
    // 2^63 is exactly representable; anything at or beyond it (either way) saturates.
    if (t >= 9223372036854775808.0) return INT64_MAX;
    if (t <= -9223372036854775808.0) return INT64_MIN;
    // Within a microsecond where double holds it (|t| < 2^53); coarser only for absurd stamps.
    if (std::fabs(offset_us) < 9e15 && std::fabs(static_cast<double>(utime)) < 9e15) return utime + std::llround(offset_us);
    return static_cast<int64_t>(t);
}

int64_t percentile(std::vector<int64_t> values, double p)
{
    if (values.empty()) return 0;
    std::sort(values.begin(), values.end());
    const auto rank = static_cast<std::size_t>(std::ceil(p / 100.0 * static_cast<double>(values.size())));
    return values[std::clamp<std::size_t>(rank, 1, values.size()) - 1];
}

}  // namespace ugv::logstat
