// What happens to the adapter's ASCII output on its way to the host, for fault tests
// (`ugv-sim servo --bit-error-rate P --truncate-every N --garbage-every S`): without I/O,
// seeded, so a run is reproducible. slcan lines carry no checksum, so these faults reach the
// host's decoder as they are.
//   truncate: every n-th frame line (t/T) loses the characters before its CR (it keeps its
//             first k characters, k random, at least the command letter);
//   garbage:  random bytes (never BEL, the adapter's error reply) between two lines;
//   bit errors: each byte, with probability P, gets one random bit inverted (last).
#pragma once

#include <cstdint>
#include <random>
#include <string>


namespace ugv::sim::servo {

struct SerialLineFaultConfig
{
    double bit_error_rate = 0;
    unsigned truncate_every = 0;  // 0 = never
    std::size_t garbage_bytes = 0;  // per burst (apply() is told when one is due)
    unsigned seed = 1;
};

class SerialLineFaults
{
public:
    explicit SerialLineFaults(const SerialLineFaultConfig& config);
    // The adapter's output (whole lines) as the host will receive it; a garbage burst goes
    // in front of it when garbage_now is set.
    std::string apply(const std::string& output, bool garbage_now);

    uint64_t lines_truncated() const { return lines_truncated_; }
    uint64_t garbage_sent() const { return garbage_sent_; }
    uint64_t bytes_damaged() const { return bytes_damaged_; }  // by a bit error

private:
    void append_line(std::string& out, const std::string& line);

    SerialLineFaultConfig config_;
    std::mt19937 rng_;
    std::mt19937 bit_error_rng_;  // its own, so the other faults fall the same with or without
    uint64_t bytes_damaged_ = 0;
    uint64_t frame_lines_ = 0;
    uint64_t lines_truncated_ = 0;
    uint64_t garbage_sent_ = 0;
};

}  // namespace ugv::sim::servo
