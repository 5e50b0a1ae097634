#include "ugv/logstat/stamp_latency.hpp"

#include <algorithm>

namespace ugv::logstat {

void StampLatency::add_input(int64_t recv_utime, int64_t utime)
{
    inputs_.push_back({recv_utime, utime});
    if (inputs_.size() > kMaxWaiting) {
        inputs_.pop_front();
        ++forgotten_;
    }
}

void StampLatency::add_output(int64_t recv_utime, int64_t utime)
{
    const auto it = std::find_if(inputs_.begin(), inputs_.end(),
                                 [&](const Input& in) { return in.utime == utime && in.recv_utime <= recv_utime; });
    if (it == inputs_.end()) return;
    // Exact in uint64; a difference beyond INT64_MAX (only in a hostile log) saturates.
    const uint64_t d = static_cast<uint64_t>(recv_utime) - static_cast<uint64_t>(it->recv_utime);
    latencies_.push_back(static_cast<int64_t>(std::min<uint64_t>(d, INT64_MAX)));
    // Inputs before the answered one were skipped by the daemon (malformed, refused).
    forgotten_ += static_cast<std::size_t>(it - inputs_.begin());
    inputs_.erase(inputs_.begin(), it + 1);
}

}  // namespace ugv::logstat
