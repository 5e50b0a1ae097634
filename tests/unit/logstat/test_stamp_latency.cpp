#include <catch2/catch.hpp>

#include <cstdint>
#include <vector>

#include "ugv/logstat/stamp_latency.hpp"

using namespace ugv::logstat;

TEST_CASE("an output's latency runs from the input with its utime")
{
    StampLatency l;
    l.add_input(1'000, 500);
    l.add_input(1'500, 1'000);
    l.add_output(1'700, 500);    // answers the first
    l.add_output(1'900, 500);    // the second output of the same input (another channel): not timed twice
    l.add_output(2'100, 1'000);
    CHECK(l.latencies_us() == std::vector<int64_t>{700, 600});
    CHECK(l.unanswered() == 0);
}

TEST_CASE("inputs the daemon dropped are counted, outputs of unknown inputs ignored")
{
    StampLatency l;
    l.add_input(1'000, 500);   // dropped (malformed)
    l.add_input(1'500, 1'000);
    l.add_output(1'600, 9'999);  // no such input
    CHECK(l.latencies_us().empty());
    l.add_output(1'800, 1'000);
    CHECK(l.latencies_us() == std::vector<int64_t>{300});
    CHECK(l.unanswered() == 1);
    l.add_input(2'000, 1'500);   // still in work at the end of the log
    CHECK(l.unanswered() == 2);
    CHECK(l.early() == 0);
}

TEST_CASE("an answer the logger received before its input is timed as 0 and counted")
{
    StampLatency l;
    // Logged after its input, but received before it.
    l.add_input(1'500, 1'000);
    l.add_output(1'400, 1'000);
    l.add_output(1'800, 1'000);  // another output of the same input: not timed twice
    // Logged before its input (a large map reassembled after the small answer).
    l.add_output(2'900, 2'000);
    CHECK(l.latencies_us() == std::vector<int64_t>{0});
    l.add_input(3'000, 2'000);
    l.add_input(3'500, 2'500);
    l.add_output(3'700, 2'500);
    CHECK(l.latencies_us() == std::vector<int64_t>{0, 0, 200});
    CHECK(l.early() == 2);
    CHECK(l.unanswered() == 0);
    // An output whose input never comes is not timed; the outputs waiting are bounded.
    for (int64_t k = 0; k < 5000; ++k) l.add_output(10'000 + k, 100'000 + k);
    l.add_input(20'000, 100'000 + 4'999);
    CHECK(l.latencies_us().size() == 4);
    l.add_input(20'001, 100'000);  // forgotten: waited behind more than the bound
    CHECK(l.latencies_us().size() == 4);
    CHECK(l.unanswered() == 1);
}

TEST_CASE("extreme receive times saturate, and the waiting inputs are bounded")
{
    StampLatency l;
    l.add_input(INT64_MIN, 1);
    l.add_output(INT64_MAX, 1);
    CHECK(l.latencies_us() == std::vector<int64_t>{INT64_MAX});
    for (int64_t k = 0; k < 5000; ++k) l.add_input(k, 100 + k);
    CHECK(l.unanswered() == 5000);
    l.add_output(6'000, 100 + 4'999);
    CHECK(l.latencies_us().back() == 6'000 - 4'999);
    CHECK(l.unanswered() == 4999);
}
