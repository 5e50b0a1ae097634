#include "ugv/logstat/channel_stats.hpp"

#include <algorithm>
#include <limits>

namespace ugv::logstat {
namespace {

constexpr uint64_t kMax = static_cast<uint64_t>(std::numeric_limits<int64_t>::max());

// b - a for a < b, exact in uint64 (every int64 difference fits there).
uint64_t distance(int64_t a, int64_t b) { return static_cast<uint64_t>(b) - static_cast<uint64_t>(a); }

// sum + add for sum >= 0, saturated at INT64_MAX.
int64_t add_saturated(int64_t sum, uint64_t add)
{
    const uint64_t room = kMax - static_cast<uint64_t>(sum);
    return add >= room ? static_cast<int64_t>(kMax) : sum + static_cast<int64_t>(add);
}

}  // namespace

double ChannelStats::rate_hz() const
{
    if (count < 2 || last_recv_utime <= first_recv_utime) return 0.0;
    return static_cast<double>(count - 1) * 1e6 / static_cast<double>(distance(first_recv_utime, last_recv_utime));
}

bool read_header(const uint8_t* data, std::size_t size, int64_t& utime, int64_t& seq)
{
    if (size < 24) return false;
    auto be64 = [&](std::size_t off) {
        uint64_t v = 0;
        for (std::size_t k = 0; k < 8; ++k) v = (v << 8) | data[off + k];
        return static_cast<int64_t>(v);
    };
    utime = be64(8);
    seq = be64(16);
    return true;
}

void StreamStats::add(const std::string& channel, const uint8_t* data, std::size_t size, int64_t recv_utime)
{
    channels_[channel].add(data, size, recv_utime);
}

void ChannelStats::add(const uint8_t* data, std::size_t size, int64_t recv_utime)
{
    ChannelStats& s = *this;
    if (s.count == 0) s.first_recv_utime = recv_utime;
    else if (recv_utime > s.last_recv_utime)
        s.max_interval_us = std::max(s.max_interval_us, add_saturated(0, distance(s.last_recv_utime, recv_utime)));
    s.last_recv_utime = recv_utime;
    ++s.count;
    s.bytes = add_saturated(s.bytes, size);
    int64_t utime = 0, seq = 0;
    if (!read_header(data, size, utime, seq)) return;
    if (s.has_seq) {
        if (seq > s.last_seq) s.seq_gaps = add_saturated(s.seq_gaps, distance(s.last_seq, seq) - 1);
        else ++s.seq_backwards;
    }
    s.has_seq = true;
    s.last_seq = seq;
}

}  // namespace ugv::logstat
