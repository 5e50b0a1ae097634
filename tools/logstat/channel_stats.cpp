#include "ugv/logstat/channel_stats.hpp"

namespace ugv::logstat {

double ChannelStats::rate_hz() const
{
    if (count < 2 || last_recv_utime <= first_recv_utime) return 0.0;
    return static_cast<double>(count - 1) * 1e6 / static_cast<double>(last_recv_utime - first_recv_utime);
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
    else if (recv_utime - s.last_recv_utime > s.max_interval_us) s.max_interval_us = recv_utime - s.last_recv_utime;
    s.last_recv_utime = recv_utime;
    ++s.count;
    s.bytes += static_cast<int64_t>(size);
    int64_t utime = 0, seq = 0;
    if (!read_header(data, size, utime, seq)) return;
    if (s.last_seq >= 0) {
        if (seq > s.last_seq + 1) s.seq_gaps += seq - s.last_seq - 1;
        if (seq <= s.last_seq) ++s.seq_backwards;
    }
    s.last_seq = seq;
}

}  // namespace ugv::logstat
