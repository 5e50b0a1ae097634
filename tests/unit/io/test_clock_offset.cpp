// UGV_CLOCK_OFFSET_S, the test aid that shifts a process's stamps (docs/time.md).
#include <catch2/catch.hpp>

#include <string>

#include "ugv/io/clock.hpp"

using ugv::io::parse_clock_offset;

TEST_CASE("UGV_CLOCK_OFFSET_S: seconds, either sign, within a day; anything else says why")
{
    std::string why;
    CHECK(parse_clock_offset(nullptr, why) == 0);
    CHECK(parse_clock_offset("", why) == 0);
    CHECK(parse_clock_offset("0.5", why) == 500'000);
    CHECK(parse_clock_offset("-1.25", why) == -1'250'000);
    CHECK(parse_clock_offset("86400", why) == 86'400'000'000);
    CHECK(parse_clock_offset("1e-6", why) == 1);
    for (const char* bad : {"abc", "0.5s", "nan", "inf", " ", "1,5"}) {
        INFO(bad);
        why.clear();
        CHECK_FALSE(parse_clock_offset(bad, why).has_value());
        CHECK(why == "not a number of seconds");
    }
    CHECK_FALSE(parse_clock_offset("86400.5", why).has_value());
    CHECK(why == "must be within -86400..86400 s");
    CHECK_FALSE(parse_clock_offset("-1e9", why).has_value());
}
