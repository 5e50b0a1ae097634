// Repeated errors, rate-limited and counted, never silenced: the first occurrence of a key is
// logged; further ones within the interval are counted and reported with the next line
// ("... (repeated 37 times in the last 5.0 s)").
#pragma once

#include <cstdint>
#include <string>
#include <unordered_map>

#include <spdlog/spdlog.h>

namespace ugv::runtime {

class RateLimitedLog
{
public:
    explicit RateLimitedLog(int64_t interval_us = 5'000'000) : interval_us_(interval_us) {}
    // Logs msg at level under key unless the same key was logged less than the interval ago.
    // now_us is a monotonic time (io::monotonic_us()); passed in so tests control it.
    // Returns true when a line was written.
    bool log(spdlog::level::level_enum level, const std::string& key, const std::string& msg, int64_t now_us);
    uint64_t suppressed_total() const { return suppressed_total_; }

private:
    struct Entry
    {
        int64_t last_us = 0;
        uint64_t suppressed = 0;
    };
    int64_t interval_us_;
    std::unordered_map<std::string, Entry> entries_;
    uint64_t suppressed_total_ = 0;
};

}  // namespace ugv::runtime
