#include <catch2/catch.hpp>

#include <thread>

#include "ugv/runtime/counters.hpp"

TEST_CASE("counters keep registration order and stable references")
{
    ugv::runtime::Counters c;
    auto& scans = c["scans"];
    c["crc_errors"];
    for (int k = 0; k < 100; ++k) c["extra_" + std::to_string(k)];  // growth must not move "scans"
    scans += 3;
    ++c["crc_errors"];
    const auto snap = c.snapshot();
    REQUIRE(snap.size() == 102);
    CHECK(snap[0] == std::make_pair(std::string("scans"), int64_t{3}));
    CHECK(snap[1] == std::make_pair(std::string("crc_errors"), int64_t{1}));
    CHECK(c.get("absent") == 0);
}

TEST_CASE("counters count exactly while another thread increments")
{
    ugv::runtime::Counters c;
    auto& frames = c["frames"];
    std::thread t([&] {
        for (int k = 0; k < 100000; ++k) ++frames;
    });
    int64_t last = 0;
    for (int k = 0; k < 1000; ++k) {
        const int64_t v = c.snapshot()[0].second;
        CHECK(v >= last);  // monotonic as seen from the status thread
        last = v;
    }
    t.join();
    CHECK(c.get("frames") == 100000);
}
