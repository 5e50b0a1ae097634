#include "ugv/logstat/stamp_latency.hpp"

#include <algorithm>

namespace ugv::logstat {

void StampLatency::add_input(int64_t recv_utime, int64_t utime)
{
    // An output logged before its input answers it as it comes: the logger finished
    // reassembling the (large) input after the (small) answer.
    const auto early = std::find_if(early_outputs_.begin(), early_outputs_.end(),
                                    [&](const Stamped& out) { return out.utime == utime; });
    if (early != early_outputs_.end()) {
        latencies_.push_back(0);
        ++early_;
        early_outputs_.erase(early);
        return;
    }
    inputs_.push_back({recv_utime, utime});
    if (inputs_.size() > kMaxWaiting) {
        inputs_.pop_front();
        ++forgotten_;
    }
}

void StampLatency::add_output(int64_t recv_utime, int64_t utime)
{
    const auto it = std::find_if(inputs_.begin(), inputs_.end(), [&](const Stamped& in) { return in.utime == utime; });
    if (it == inputs_.end()) {
        // Not (yet) logged: its input may follow; an output of an input never logged is ignored.
        early_outputs_.push_back({recv_utime, utime});
        if (early_outputs_.size() > kMaxWaiting) early_outputs_.pop_front();
        return;
    }
    if (it->recv_utime > recv_utime) {
        latencies_.push_back(0);  // the logger stamped the input after the answer
        ++early_;
    } else {
        // Exact in uint64; a difference beyond INT64_MAX (only in a hostile log) saturates.
        const uint64_t d = static_cast<uint64_t>(recv_utime) - static_cast<uint64_t>(it->recv_utime);
        latencies_.push_back(static_cast<int64_t>(std::min<uint64_t>(d, INT64_MAX)));
    }
    // Inputs before the answered one were skipped by the daemon (malformed, refused).
    forgotten_ += static_cast<std::size_t>(it - inputs_.begin());
    inputs_.erase(inputs_.begin(), it + 1);
}

}  // namespace ugv::logstat
