// Exponential back-off for reopening a device: 0.1 s, 0.2 s, 0.4 s, ... up to a cap.
#pragma once

#include <algorithm>
#include <cstdint>

namespace ugv::runtime {

class Backoff
{
public:
    explicit Backoff(int64_t initial_us = 100'000, int64_t max_us = 2'000'000)
        : initial_us_(initial_us), max_us_(max_us), next_us_(initial_us) {}
    // The wait before the next attempt, and doubles the one after.
    int64_t next()
    {
        const int64_t d = next_us_;
        next_us_ = std::min(next_us_ * 2, max_us_);
        return d;
    }
    void reset() { next_us_ = initial_us_; }

private:
    int64_t initial_us_, max_us_, next_us_;
};

}  // namespace ugv::runtime
