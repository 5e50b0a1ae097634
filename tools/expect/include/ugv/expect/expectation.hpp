// What ugv-expect checks over a window of traffic on one channel, and its one-line verdict.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "ugv/expect/where_expression.hpp"
#include "ugv/logstat/channel_stats.hpp"

namespace ugv::expect {

struct Expectation
{
    std::string channel;
    double window_s = 5.0;
    std::optional<double> rate_min_hz, rate_max_hz;  // --rate MIN:MAX
    std::optional<int64_t> max_gap;                  // --max-gap N: seq gaps allowed
    std::optional<int64_t> min_count;                // --min-count N
    std::optional<WhereExpression> where;            // every message must satisfy it
};

// Parses "35:40", "35:" or ":40" into the expectation. Throws std::invalid_argument.
void parse_rate(const std::string& text, Expectation& e);

struct Observation
{
    logstat::ChannelStats stats;
    int64_t where_ok = 0;
    int64_t where_failed = 0;
    int64_t undecodable = 0;
    std::string first_failing;  // the first message (JSON) that failed --where
};

struct Verdict
{
    bool pass = false;
    std::string line;  // "LMS_SCAN: 187 msgs in 5.0 s, 37.4 Hz [35, 40] ok, ... -> PASS"
};

Verdict judge(const Expectation& e, const Observation& o);

}  // namespace ugv::expect
