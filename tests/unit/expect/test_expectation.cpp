#include <catch2/catch.hpp>

#include "ugv/expect/expectation.hpp"

using namespace ugv::expect;

namespace {
Observation seen(int64_t count, int64_t gaps, int64_t backwards = 0)
{
    Observation o;
    o.stats.count = count;
    o.stats.seq_gaps = gaps;
    o.stats.seq_backwards = backwards;
    return o;
}
}  // namespace

TEST_CASE("rate bounds parse from MIN:MAX with either side open")
{
    Expectation e;
    parse_rate("35:40", e);
    CHECK(*e.rate_min_hz == 35);
    CHECK(*e.rate_max_hz == 40);
    Expectation lo;
    parse_rate("9.5:", lo);
    CHECK(*lo.rate_min_hz == 9.5);
    CHECK_FALSE(lo.rate_max_hz);
    Expectation bad;
    CHECK_THROWS_WITH(parse_rate("40:35", bad), "--rate '40:35': MIN is above MAX");
    CHECK_THROWS_WITH(parse_rate("fast", bad), "--rate takes MIN:MAX in Hz (either may be empty)");
}

TEST_CASE("the verdict passes only when every asked check holds, and says so in one line")
{
    Expectation e;
    e.channel = "LMS_SCAN";
    e.window_s = 5.0;
    parse_rate("35:40", e);
    e.max_gap = 0;
    auto v = judge(e, seen(187, 0));
    CHECK(v.pass);
    CHECK(v.line == "LMS_SCAN: 187 msgs in 5.0 s, 37.40 Hz [35.000, 40.000] ok, seq gaps 0 (max 0) ok -> PASS");
    v = judge(e, seen(150, 0));
    CHECK_FALSE(v.pass);
    CHECK(v.line.find("30.00 Hz [35.000, 40.000] FAIL") != std::string::npos);
    v = judge(e, seen(187, 2));
    CHECK_FALSE(v.pass);
    CHECK(v.line.find("seq gaps 2 (max 0) FAIL") != std::string::npos);
    v = judge(e, seen(187, 0, 1));
    CHECK_FALSE(v.pass);
    CHECK(v.line.find("seq went back 1x FAIL") != std::string::npos);
}

TEST_CASE("nothing seen never passes, and --where counts failing messages")
{
    Expectation e;
    e.channel = "POSE";
    CHECK_FALSE(judge(e, seen(0, 0)).pass);
    e.where.emplace("status == 1");
    Observation o = seen(10, 0);
    o.where_ok = 9;
    o.where_failed = 1;
    const auto v = judge(e, o);
    CHECK_FALSE(v.pass);
    CHECK(v.line == "POSE: 10 msgs in 5.0 s, 2.00 Hz, where 'status == 1': 9/10 FAIL -> FAIL");
}
