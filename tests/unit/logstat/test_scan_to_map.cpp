#include <catch2/catch.hpp>

#include <limits>
#include <vector>

#include "ugv/logstat/scan_to_map.hpp"

using namespace ugv::logstat;

TEST_CASE("a scan's latency runs to the first map whose time covers its last beam")
{
    ScanToMapLatency l;
    l.add_scan(1'000, 900);    // last beam at 900, received at 1000
    l.add_scan(2'000, 1'900);
    l.add_scan(3'000, 2'900);
    l.add_map(2'500, 1'000);   // covers the first scan only
    REQUIRE(l.latencies_us() == std::vector<int64_t>{1'500});
    l.add_map(4'000, 2'000);   // the second; the third's beams are later than 2000
    l.add_map(5'000, 3'500);   // the third
    CHECK(l.latencies_us() == std::vector<int64_t>{1'500, 2'000, 2'000});
    CHECK(l.pending() == 0);
}

TEST_CASE("a map published before a scan arrived does not hold it")
{
    ScanToMapLatency l;
    l.add_scan(10'000, 900);   // a late scan (received after the map below)
    l.add_map(5'000, 1'000);
    CHECK(l.latencies_us().empty());
    l.add_map(12'000, 1'500);
    CHECK(l.latencies_us() == std::vector<int64_t>{2'000});
}

TEST_CASE("percentiles by nearest rank")
{
    CHECK(percentile({}, 50) == 0);
    CHECK(percentile({5, 1, 3, 2, 4}, 50) == 3);
    CHECK(percentile({5, 1, 3, 2, 4}, 99) == 5);
    CHECK(percentile({5, 1, 3, 2, 4}, 0) == 1);
}

TEST_CASE("scan times from a hostile log saturate instead of overflowing")
{
    constexpr int64_t kMin = std::numeric_limits<int64_t>::min();
    constexpr int64_t kMax = std::numeric_limits<int64_t>::max();
    CHECK(shifted_utime(1'000, 26'666.4) == 27'666);
    CHECK(shifted_utime(kMax, 1e6) == kMax);
    CHECK(shifted_utime(kMin, -1e6) == kMin);
    CHECK(shifted_utime(0, 1e300) == kMax);
    CHECK(shifted_utime(5, std::numeric_limits<double>::quiet_NaN()) == 5);
    CHECK(shifted_utime(5, std::numeric_limits<double>::infinity()) == 5);
    ScanToMapLatency l;
    l.add_scan(kMin, kMin);
    l.add_map(kMax, kMax);
    CHECK(l.latencies_us() == std::vector<int64_t>{kMax});
}
