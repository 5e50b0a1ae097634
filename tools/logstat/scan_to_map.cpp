#include "ugv/logstat/scan_to_map.hpp"

#include <algorithm>
#include <cmath>

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
            latencies_.push_back(recv_utime - it->recv_utime);
            it = pending_.erase(it);
        } else if (it->last_beam_utime > map_utime) {
            break;
        } else {
            ++it;
        }
    }
}

int64_t percentile(std::vector<int64_t> values, double p)
{
    if (values.empty()) return 0;
    std::sort(values.begin(), values.end());
    const auto rank = static_cast<std::size_t>(std::ceil(p / 100.0 * static_cast<double>(values.size())));
    return values[std::clamp<std::size_t>(rank, 1, values.size()) - 1];
}

}  // namespace ugv::logstat
