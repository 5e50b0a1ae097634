#include "ugv/runtime/rate_limited_log.hpp"

#include <cstdio>

namespace ugv::runtime {

bool RateLimitedLog::log(spdlog::level::level_enum level, const std::string& key, const std::string& msg, int64_t now_us)
{
    auto [it, fresh] = entries_.try_emplace(key);
    Entry& e = it->second;
    if (!fresh && now_us - e.last_us < interval_us_) {
        ++e.suppressed;
        ++suppressed_total_;
        return false;
    }
    if (e.suppressed > 0) {
        char tail[96];
        std::snprintf(tail, sizeof tail, " (repeated %llu times in the last %.1f s)",
                      static_cast<unsigned long long>(e.suppressed), static_cast<double>(now_us - e.last_us) / 1e6);
        spdlog::log(level, "{}{}", msg, tail);
    } else {
        spdlog::log(level, "{}", msg);
    }
    e.last_us = now_us;
    e.suppressed = 0;
    return true;
}

}  // namespace ugv::runtime
