#include <catch2/catch.hpp>

#include "ugv/latency/latency_meter.hpp"

using namespace ugv::latency;

TEST_CASE("quantiles by nearest rank")
{
    std::vector<int64_t> v;
    for (int64_t k = 1; k <= 100; ++k) v.push_back(k);
    CHECK(quantile(v, 0.50) == 50);
    CHECK(quantile(v, 0.99) == 99);
    CHECK(quantile(v, 1.0) == 100);
    CHECK(quantile({7}, 0.99) == 7);
    CHECK(quantile({}, 0.5) == 0);
}

TEST_CASE("each message pairs with the latest start before it; unpaired ones are skipped")
{
    LatencyMeter m;
    CHECK_FALSE(m.on_to(1000));  // nothing started yet
    m.on_from(1000);
    CHECK(m.on_to(1300));
    m.on_from(2000);
    m.on_from(2100);  // the chunk that completed the telegram
    CHECK(m.on_to(2500));
    CHECK_FALSE(m.on_to(2000));  // received before its start: a clock step, not a latency
    CHECK(m.on_to(5000, 4990));  // self mode: its own stamp
    const auto s = m.summary();
    CHECK(s.samples == 3);
    CHECK(s.min_us == 10);
    CHECK(s.p50_us == 300);
    CHECK(s.max_us == 400);
}
