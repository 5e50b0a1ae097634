// ugv-logstat on a log with injected sequence numbers and receive times at the int64
// extremes: the counts saturate at INT64_MAX (they once came out as -1408329726962500532),
// a wrap is one step back, and a channel name with quotes stays valid JSON.
#include <catch2/catch.hpp>

#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "ugv/bus/bus.hpp"
#include "ugv/bus/typed.hpp"
#include "ugv/pose_t.hpp"
#include "ugv_test/process.hpp"

using namespace ugv;

namespace {

constexpr int64_t kMin = std::numeric_limits<int64_t>::min();
constexpr int64_t kMax = std::numeric_limits<int64_t>::max();

// The value of "key": in the JSON line of channel ch (an integer, as text).
std::string field(const std::string& json_lines, const std::string& ch, const std::string& key)
{
    std::istringstream in(json_lines);
    std::string line;
    while (std::getline(in, line)) {
        if (line.find("\"channel\":\"" + ch + "\"") == std::string::npos) continue;
        const auto p = line.find("\"" + key + "\":");
        if (p == std::string::npos) return "";
        const auto start = p + key.size() + 3;
        return line.substr(start, line.find_first_of(",}", start) - start);
    }
    return "";
}

}  // namespace

TEST_CASE("ugv-logstat: injected extreme sequence numbers and times saturate, never overflow")
{
    test::TempDir dir;
    {
        int64_t t = 0;
        auto w = bus::open_log_writer(dir / "x.lcm", [&] { return t; });
        const auto put = [&](const std::string& ch, int64_t seq, int64_t recv) {
            pose_t p{};
            p.utime = 1'700'000'000'000'000;
            p.seq = seq;
            t = recv;
            REQUIRE(bus::publish(*w, ch, p));
        };
        // Up to INT64_MAX, a wrap, up across the whole range, and up to INT64_MAX again: the
        // sum of the gaps is past INT64_MAX three times over.
        for (const int64_t s : {int64_t{0}, kMax, kMin, int64_t{0}, kMax}) put("POSE", s, 1'000);
        // Negative sequence numbers are counted like any other.
        for (const int64_t s : {kMin, kMin + 3, kMin + 4}) put("IMU", s, 2'000);
        // Receive times (the log's event stamps) from one end to the other.
        put("TIMES", 1, 0);
        put("TIMES", 2, kMax);
        put("QUOTE\"D", 1, 3'000);
    }
    REQUIRE(test::run({test::bin("ugv-logstat"), dir / "x.lcm", "--json"}, dir / "out", dir / "err", 30.0) == 0);
    const std::string out = test::read_file(dir / "out");
    INFO(out);
    CHECK(field(out, "POSE", "seq_gaps") == std::to_string(kMax));
    CHECK(field(out, "POSE", "seq_backwards") == "1");
    CHECK(field(out, "IMU", "seq_gaps") == "2");
    CHECK(field(out, "IMU", "seq_backwards") == "0");
    CHECK(field(out, "TIMES", "count") == "2");
    CHECK(field(out, "QUOTE\\\"D", "count") == "1");
    CHECK(out.find('-') == std::string::npos);  // no negative count anywhere
    // The table prints the same numbers.
    REQUIRE(test::run({test::bin("ugv-logstat"), dir / "x.lcm"}, dir / "out", dir / "err", 30.0) == 0);
    CHECK(test::read_file(dir / "out").find(std::to_string(kMax)) != std::string::npos);
}
