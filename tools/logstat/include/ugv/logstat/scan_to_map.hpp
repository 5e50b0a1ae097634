// Latency from a laser scan to the first terrain map that contains its points, from the
// receive times in an LCM log: a map referenced to time T holds every scan whose last beam
// was measured by T, so a scan's latency is the receive time of the first map with
// utime >= its last beam time minus the receive time of the scan itself (which is the
// driver's publish time, 0.1-0.2 ms after the telegram's last byte: docs/lms.md).
#pragma once

#include <cstdint>
#include <deque>
#include <vector>

namespace ugv::logstat {

class ScanToMapLatency
{
public:
    void add_scan(int64_t recv_utime, int64_t last_beam_utime);
    void add_map(int64_t recv_utime, int64_t map_utime);
    // One latency (us) per scan that a map has covered, in scan order.
    const std::vector<int64_t>& latencies_us() const { return latencies_; }
    std::size_t pending() const { return pending_.size(); }

private:
    struct Scan
    {
        int64_t recv_utime, last_beam_utime;
    };
    std::deque<Scan> pending_;
    std::vector<int64_t> latencies_;
};

// utime + offset_us rounded to the microsecond, saturated at the int64 limits; utime itself
// for a non-finite offset (a log may hold any scan header).
int64_t shifted_utime(int64_t utime, double offset_us);

// The p-th percentile (0-100, nearest rank) of values; 0 when empty.
int64_t percentile(std::vector<int64_t> values, double p);

}  // namespace ugv::logstat
