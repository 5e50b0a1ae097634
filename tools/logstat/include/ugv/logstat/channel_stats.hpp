// Per-channel statistics of a stream of ugv messages: count, rate, and gaps in `seq`.
// Every ugv type begins with the 8-byte fingerprint, then int64 utime and int64 seq, big-endian
// (LCM encoding), so seq is read without decoding the whole message. A log may hold any
// values there (a hostile or broken publisher): sums and differences saturate at INT64_MAX
// instead of overflowing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>

namespace ugv::logstat {

struct ChannelStats
{
    int64_t count = 0;
    int64_t first_recv_utime = 0;
    int64_t last_recv_utime = 0;
    int64_t bytes = 0;
    int64_t seq_gaps = 0;        // messages missing between consecutive seq values (saturates)
    int64_t seq_backwards = 0;   // seq went down or repeated (a publisher restarted, reordering, a wrap)
    bool has_seq = false;        // last_seq holds a message's seq (any int64 is one)
    int64_t last_seq = 0;
    int64_t max_interval_us = 0; // largest time between two consecutive messages (saturates)

    // Counts one message received at recv_utime.
    void add(const uint8_t* data, std::size_t size, int64_t recv_utime);
    // Messages per second between the first and last message (0 with fewer than 2).
    double rate_hz() const;
};

class StreamStats
{
public:
    void add(const std::string& channel, const uint8_t* data, std::size_t size, int64_t recv_utime);
    const std::map<std::string, ChannelStats>& channels() const { return channels_; }

private:
    std::map<std::string, ChannelStats> channels_;
};

// utime and seq from the first 24 bytes of a ugv message; false when it is shorter.
bool read_header(const uint8_t* data, std::size_t size, int64_t& utime, int64_t& seq);

}  // namespace ugv::logstat
