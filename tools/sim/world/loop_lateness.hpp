// How late the simulator's single loop ran: the longest time between two turns and how many
// turns came more than 10 ms after the one before. The loop waits at most 1 ms, so a long gap
// means the process was not scheduled (a loaded or stalled host), and every device it drives
// was late by as much. Reported when the world ends, for reading a failed run.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>

namespace ugv::sim::world {

class LoopLateness
{
public:
    static constexpr int64_t kLateUs = 10'000;

    void add(int64_t now_utime)
    {
        if (last_ != 0) {
            const int64_t gap = now_utime - last_;
            max_gap_us_ = std::max(max_gap_us_, gap);
            if (gap > kLateUs) ++late_turns_;
        }
        last_ = now_utime;
    }
    int64_t max_gap_us() const { return max_gap_us_; }
    uint64_t late_turns() const { return late_turns_; }
    std::string summary() const
    {
        char buf[128];
        std::snprintf(buf, sizeof buf, "loop: longest gap %.1f ms, %llu gaps over %lld ms",
                      static_cast<double>(max_gap_us_) * 1e-3, static_cast<unsigned long long>(late_turns_),
                      static_cast<long long>(kLateUs / 1000));
        return buf;
    }

private:
    int64_t last_ = 0;
    int64_t max_gap_us_ = 0;
    uint64_t late_turns_ = 0;
};

}  // namespace ugv::sim::world
