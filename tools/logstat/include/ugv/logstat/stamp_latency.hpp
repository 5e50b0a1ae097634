// The latency a processing daemon adds, from the receive times in an LCM log: its output
// carries its input's utime (a TRAVERSABILITY_MAP or ARCS the TERRAIN_MAP's), so an output's
// latency is its receive time minus that of the input with the same utime (the first such
// input logged). Inputs never answered are counted, not timed. An answer received before its
// input (lcm-logger finishes reassembling a large input after a small answer to it: its
// stamps bound the daemon's latency only loosely) counts as 0 and is counted too.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

namespace ugv::logstat {

class StampLatency
{
public:
    void add_input(int64_t recv_utime, int64_t utime);
    void add_output(int64_t recv_utime, int64_t utime);
    // One latency (us) per output matched to an input, in the order they were matched.
    const std::vector<int64_t>& latencies_us() const { return latencies_; }
    // Inputs no output has answered (yet): dropped, refused or still in work at the end.
    std::size_t unanswered() const { return inputs_.size() + forgotten_; }
    // Of the latencies, the answers received before their input (timed as 0).
    std::size_t early() const { return early_; }

private:
    struct Stamped  // a logged message: when it was received, and the utime it carries
    {
        int64_t recv_utime, utime;
    };
    // The newest inputs; an output answers one of them or none (a log holds hours of maps).
    static constexpr std::size_t kMaxWaiting = 1024;
    std::deque<Stamped> inputs_;
    std::deque<Stamped> early_outputs_;  // outputs whose input was not logged yet
    std::size_t forgotten_ = 0;
    std::size_t early_ = 0;
    std::vector<int64_t> latencies_;
};

}  // namespace ugv::logstat
