#include <catch2/catch.hpp>

#include <limits>
#include <vector>

#include "ugv/bus/typed.hpp"
#include "ugv/logstat/channel_stats.hpp"
#include "ugv/pose_t.hpp"

namespace {
std::vector<uint8_t> encode(int64_t utime, int64_t seq)
{
    ugv::pose_t p{};
    p.utime = utime;
    p.seq = seq;
    std::vector<uint8_t> buf(static_cast<std::size_t>(p.getEncodedSize()));
    p.encode(buf.data(), 0, static_cast<int>(buf.size()));
    return buf;
}
}  // namespace

TEST_CASE("seq and utime are read from the header of any ugv message")
{
    const auto b = encode(1'700'000'000'123'456, 987654321);
    int64_t utime = 0, seq = 0;
    REQUIRE(ugv::logstat::read_header(b.data(), b.size(), utime, seq));
    CHECK(utime == 1'700'000'000'123'456);
    CHECK(seq == 987654321);
    CHECK_FALSE(ugv::logstat::read_header(b.data(), 23, utime, seq));
}

TEST_CASE("rate, gaps and backward steps are counted per channel")
{
    ugv::logstat::StreamStats s;
    // POSE at 10 Hz for 2 s with seq 3 and 4 missing; then the publisher restarts at seq 0.
    int64_t t = 0;
    for (int64_t seq = 0; seq < 21; ++seq) {
        if (seq == 3 || seq == 4) {
            t += 100'000;
            continue;
        }
        const auto b = encode(t, seq);
        s.add("POSE", b.data(), b.size(), t);
        t += 100'000;
    }
    const auto b = encode(t, 0);
    s.add("POSE", b.data(), b.size(), t);
    const auto other = encode(0, 5);
    s.add("IMU", other.data(), other.size(), 0);

    const auto& pose = s.channels().at("POSE");
    CHECK(pose.count == 20);
    CHECK(pose.seq_gaps == 2);
    CHECK(pose.seq_backwards == 1);
    CHECK(pose.max_interval_us == 300'000);
    CHECK(pose.rate_hz() == Approx(19.0 / 2.1));
    CHECK(s.channels().at("IMU").rate_hz() == 0.0);
}

TEST_CASE("extreme sequence numbers and receive times saturate, never overflow")
{
    constexpr int64_t kMin = std::numeric_limits<int64_t>::min();
    constexpr int64_t kMax = std::numeric_limits<int64_t>::max();
    const auto feed = [](const std::vector<int64_t>& seqs, const std::vector<int64_t>& times = {}) {
        ugv::logstat::ChannelStats c;
        for (std::size_t i = 0; i < seqs.size(); ++i) {
            const auto b = encode(0, seqs[i]);
            c.add(b.data(), b.size(), times.empty() ? static_cast<int64_t>(i) * 1000 : times[i]);
        }
        return c;
    };
    // The whole int64 range in one step: 2^64 - 2 missing, saturated (was a negative count).
    auto c = feed({kMin, kMax});
    CHECK(c.seq_gaps == kMax);
    CHECK(c.seq_backwards == 0);
    // Negative seqs are seqs too (-1 once meant "none yet").
    c = feed({kMin, kMin + 3, -1, 0});
    CHECK(c.seq_gaps == 2 + (-1 - (kMin + 3) - 1));
    CHECK(c.seq_backwards == 0);
    // Up to INT64_MAX, a wrap to INT64_MIN, up again: the sum saturates and stays there.
    c = feed({0, kMax, kMin, kMax, 5, 6});
    CHECK(c.seq_gaps == kMax);
    CHECK(c.seq_backwards == 2);
    // A wrap alone is one step back; a repeat too.
    c = feed({kMax - 1, kMax, kMin, kMin + 1, kMin + 1});
    CHECK(c.seq_gaps == 0);
    CHECK(c.seq_backwards == 2);
    // Receive times from one end of int64 to the other.
    c = feed({1, 2, 3}, {kMin, kMax, kMax});
    CHECK(c.max_interval_us == kMax);
    CHECK(c.rate_hz() > 0.0);
    CHECK(c.rate_hz() < 1e-9);
    c = feed({1, 2}, {kMax, kMin});  // backwards in time: no interval, no rate
    CHECK(c.max_interval_us == 0);
    CHECK(c.rate_hz() == 0.0);
}
