// Latency from an event to the message it caused, on one host (one CLOCK_REALTIME):
//   from-stamp: the `utime` field of the latest message on a --from channel (raw_bytes_t:
//               the arrival time of the chunk that completed a telegram), or its receive time;
//   to-stamp:   the receive time of the message on the --to channel.
// With no --from channel, the --to message's own utime is the start (a receive-time stamp).
#pragma once

#include <cstdint>
#include <vector>

namespace ugv::latency {

class LatencyMeter
{
public:
    // A --from message: its start time (us).
    void on_from(int64_t start_utime) { last_from_ = start_utime; }
    // A --to message received at recv_utime; start_utime is its own stamp (self mode) or
    // -1 to use the latest --from. Returns false when there is nothing to pair it with.
    bool on_to(int64_t recv_utime, int64_t start_utime = -1);
    struct Summary
    {
        std::size_t samples = 0;
        double p50_us = 0, p99_us = 0, max_us = 0, min_us = 0;
    };
    Summary summary() const;

private:
    int64_t last_from_ = -1;
    std::vector<int64_t> samples_us_;
};

// The q-quantile (0..1) of values by the nearest-rank method; 0 for none.
double quantile(std::vector<int64_t> values, double q);

}  // namespace ugv::latency
