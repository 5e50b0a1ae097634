// The lcm-logger log scanner: events as lcm-logger writes them, and damage skipped without
// losing the events around it.
#include <catch2/catch.hpp>

#include <lcm/lcm-cpp.hpp>

#include <fstream>
#include <iterator>

#include "ugv/mcap/lcm_log_scanner.hpp"
#include "ugv/pose_t.hpp"
#include "ugv_test/encoded.hpp"
#include "ugv_test/process.hpp"

using namespace ugv;

namespace {

// A log of n poses on "POSE" written by liblcm, as bytes.
std::vector<uint8_t> log_bytes(int n)
{
    test::TempDir dir;
    const std::string path = dir / "a.lcm";
    {
        lcm::LogFile log(path, "w");
        REQUIRE(log.good());
        for (int k = 0; k < n; ++k) {
            pose_t p{};
            p.utime = k;
            p.seq = k;
            test::write_event(log, 1000 + k, "POSE", p);
        }
    }
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

std::vector<int64_t> times(const std::vector<uint8_t>& b, mcap::LcmLogScanner* out = nullptr)
{
    mcap::LcmLogScanner s(b.data(), b.size());
    std::vector<int64_t> t;
    for (mcap::LogEvent e; s.next(e);) {
        CHECK(e.channel == "POSE");
        t.push_back(e.utime);
    }
    if (out) *out = s;
    return t;
}

}  // namespace

TEST_CASE("every event of a log written by liblcm, in order")
{
    const auto b = log_bytes(5);
    mcap::LcmLogScanner s(b.data(), b.size());
    CHECK(times(b, &s) == std::vector<int64_t>{1000, 1001, 1002, 1003, 1004});
    CHECK(s.skipped_bytes() == 0);
    mcap::LcmLogScanner again(b.data(), b.size());
    mcap::LogEvent e;
    REQUIRE(again.next(e));
    pose_t p{};
    CHECK(p.decode(e.data, 0, static_cast<int>(e.size)) == static_cast<int>(e.size));
}

TEST_CASE("a log cut in its last event keeps every event before it")
{
    auto b = log_bytes(5);
    const std::size_t event = b.size() / 5;
    b.resize(b.size() - event / 2);
    mcap::LcmLogScanner s(nullptr, 0);
    CHECK(times(b, &s) == std::vector<int64_t>{1000, 1001, 1002, 1003});
    CHECK(s.skipped_bytes() == event - event / 2);
    CHECK(s.first_damage() == 4 * event);
}

TEST_CASE("damage in the middle is skipped: the events after it are found again")
{
    auto b = log_bytes(5);
    const std::size_t event = b.size() / 5;
    b[2 * event] ^= 0xff;            // event 2's sync word
    b[3 * event + 22] = 0x7f;        // event 3's channel length: impossible
    mcap::LcmLogScanner s(nullptr, 0);
    CHECK(times(b, &s) == std::vector<int64_t>{1000, 1001, 1004});
    CHECK(s.skipped_bytes() == 2 * event);
    CHECK(s.damaged_stretches() == 1);
    CHECK(s.first_damage() == 2 * event);
}

TEST_CASE("bytes that are not a log give no event")
{
    const std::vector<uint8_t> b(1000, 0x41);
    mcap::LcmLogScanner s(b.data(), b.size());
    mcap::LogEvent e;
    CHECK_FALSE(s.next(e));
    CHECK(s.skipped_bytes() == 1000);
}
