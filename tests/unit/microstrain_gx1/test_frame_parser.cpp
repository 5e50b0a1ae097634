// Frame parser: resynchronisation, checksum rejection, any chunk split, first-byte dating.
#include <catch2/catch.hpp>

#include <random>

#include "ugv/microstrain_gx1/frame_parser.hpp"

using namespace ugv::microstrain_gx1;
using Bytes = std::vector<uint8_t>;

namespace {

// A 0x31 reply whose payload contains the byte 0x31 several times.
Bytes euler_frame(uint16_t ticks)
{
    return encode_reply(0x31, {0x0031, 0x3131, 0xFF31, 0x0100, 0x0200, 0x0300, 0x3100, 0x0031, 0x0010, ticks});
}

std::vector<Frame> parse_all(FrameParser& p, const Bytes& bytes)
{
    p.feed(bytes.data(), bytes.size());
    std::vector<Frame> out;
    Frame f;
    while (p.next(f)) out.push_back(f);
    return out;
}

Bytes concat(std::initializer_list<Bytes> parts)
{
    Bytes out;
    for (const Bytes& b : parts) out.insert(out.end(), b.begin(), b.end());
    return out;
}

}  // namespace

TEST_CASE("a clean stream gives every frame with its words", "[gx1][parser]")
{
    FrameParser p;
    auto frames = parse_all(p, concat({euler_frame(1), euler_frame(2), encode_reply(0xF0, {0x0302})}));
    REQUIRE(frames.size() == 3);
    CHECK(frames[0].command == 0x31);
    CHECK(frames[0].nwords == 10);
    CHECK(frames[0].words[1] == 0x3131);
    CHECK(frames[0].word_signed(2) == static_cast<int16_t>(0xFF31));
    CHECK(frames[0].ticks() == 1);
    CHECK(frames[1].ticks() == 2);
    CHECK(frames[2].command == 0xF0);
    CHECK(frames[2].words[0] == 0x0302);
    CHECK(p.counters().frames == 3);
    CHECK(p.counters().resyncs == 0);
    CHECK(p.counters().bytes_skipped == 0);
    CHECK(p.buffered() == 0);
}

TEST_CASE("resynchronises after garbage that contains the command byte", "[gx1][parser]")
{
    FrameParser p;
    p.accept_only({0x31, 0x10});
    // Garbage holding 0x31 and a truncated copy of a real frame (a false start whose length
    // runs into the next good frame), then good frames.
    Bytes good1 = euler_frame(100);
    Bytes garbage = {0x31, 0x00, 0x31, 0x31, 0x55};
    garbage.insert(garbage.end(), good1.begin(), good1.begin() + 9);
    auto frames = parse_all(p, concat({garbage, euler_frame(101), euler_frame(102)}));
    REQUIRE(frames.size() == 2);
    CHECK(frames[0].ticks() == 101);
    CHECK(frames[1].ticks() == 102);
    CHECK(p.counters().bytes_skipped == garbage.size());
    CHECK(p.counters().resyncs == 1);
}

TEST_CASE("a frame with a bad checksum is never returned, the next one is", "[gx1][parser]")
{
    FrameParser p;
    Bytes bad = euler_frame(7);
    bad[5] ^= 0x40;  // one payload bit flipped
    auto frames = parse_all(p, concat({euler_frame(6), bad, euler_frame(8)}));
    REQUIRE(frames.size() == 2);
    CHECK(frames[0].ticks() == 6);
    CHECK(frames[1].ticks() == 8);
    CHECK(p.counters().checksum_errors == 1);
    CHECK(p.counters().resyncs == 1);
    CHECK(p.counters().bytes_skipped == bad.size());

    // The checksum bytes themselves damaged: same outcome.
    Bytes bad_sum = euler_frame(9);
    bad_sum.back() ^= 0x01;
    frames = parse_all(p, concat({bad_sum, euler_frame(10)}));
    REQUIRE(frames.size() == 1);
    CHECK(frames[0].ticks() == 10);
    CHECK(p.counters().checksum_errors == 2);
}

TEST_CASE("on random noise the parser agrees with a naive scan and returns no bad frame", "[gx1][parser]")
{
    std::mt19937 rng(1234);
    std::uniform_int_distribution<int> byte(0, 255);
    Bytes noise(200000);
    for (auto& b : noise) b = static_cast<uint8_t>(byte(rng));
    // Plant good frames at random places, so both accepting and skipping are exercised.
    for (int k = 0; k < 50; ++k) {
        const Bytes f = euler_frame(static_cast<uint16_t>(k));
        const std::size_t at = static_cast<std::size_t>(rng() % (noise.size() - f.size()));
        std::copy(f.begin(), f.end(), noise.begin() + static_cast<std::ptrdiff_t>(at));
    }
    // Reference: at each offset take a verifying candidate, else move one byte.
    std::vector<std::size_t> expected;
    for (std::size_t i = 0; i < noise.size();) {
        const std::size_t len = reply_length(noise[i]);
        if (len == 0) {
            ++i;
            continue;
        }
        if (i + len > noise.size()) break;
        const uint16_t sent = static_cast<uint16_t>(noise[i + len - 2] << 8 | noise[i + len - 1]);
        if (checksum(noise[i], &noise[i + 1], (len - 3) / 2) == sent) {
            expected.push_back(i);
            i += len;
        } else {
            ++i;
        }
    }
    FrameParser p;
    std::vector<Frame> frames;
    Frame f;
    for (std::size_t at = 0; at < noise.size(); at += 1000) {
        p.feed(noise.data() + at, std::min<std::size_t>(1000, noise.size() - at));
        while (p.next(f)) frames.push_back(f);
    }
    REQUIRE(frames.size() == expected.size());
    CHECK(frames.size() >= 45);  // most planted frames survive the noise around them
    for (std::size_t k = 0; k < frames.size(); ++k) {
        const Bytes& b = noise;
        const std::size_t i = expected[k];
        CHECK(frames[k].command == b[i]);
        CHECK(frames[k].words[0] == static_cast<uint16_t>(b[i + 1] << 8 | b[i + 2]));
    }
}

TEST_CASE("frames split at every byte position decode identically", "[gx1][parser]")
{
    const Bytes stream = concat({euler_frame(1), encode_reply(0x0C, std::vector<uint16_t>(14, 0x0C0C)), euler_frame(3)});
    for (std::size_t cut = 0; cut <= stream.size(); ++cut) {
        FrameParser p;
        std::vector<Frame> frames;
        Frame f;
        p.feed(stream.data(), cut);
        while (p.next(f)) frames.push_back(f);
        p.feed(stream.data() + cut, stream.size() - cut);
        while (p.next(f)) frames.push_back(f);
        INFO("cut at " << cut);
        REQUIRE(frames.size() == 3);
        CHECK(frames[0].ticks() == 1);
        CHECK(frames[1].command == 0x0C);
        CHECK(frames[1].words[13] == 0x0C0C);
        CHECK(frames[2].ticks() == 3);
        CHECK(p.counters().bytes_skipped == 0);
    }
    // And one byte per feed.
    FrameParser p;
    std::size_t count = 0;
    Frame f;
    for (uint8_t b : stream) {
        p.feed(&b, 1);
        while (p.next(f)) ++count;
    }
    CHECK(count == 3);
}

TEST_CASE("first-byte time: chunk arrival minus the bytes after it", "[gx1][parser]")
{
    // 38400 baud 8N1: 260.4 us per byte. A chunk of 2 frames (46 bytes) read at t = 1e6 us:
    // frame 0 starts 45 bytes before the chunk's last byte, frame 1 22 bytes before.
    const double byte_us = 1e6 / 3840.0;
    FrameParser p(byte_us);
    const Bytes stream = concat({euler_frame(1), euler_frame(2)});
    p.feed(stream.data(), stream.size(), 1'000'000);
    Frame f;
    REQUIRE(p.next(f));
    CHECK(f.first_byte_utime == 1'000'000 - std::llround(45 * byte_us));
    REQUIRE(p.next(f));
    CHECK(f.first_byte_utime == 1'000'000 - std::llround(22 * byte_us));

    // A frame split over two chunks is dated by the chunk holding its first byte.
    p.feed(stream.data(), 10, 2'000'000);
    p.feed(stream.data() + 10, 13, 2'005'000);
    REQUIRE(p.next(f));
    CHECK(f.first_byte_utime == 2'000'000 - std::llround(9 * byte_us));
}

TEST_CASE("clear drops a partial frame", "[gx1][parser]")
{
    FrameParser p;
    const Bytes frame = euler_frame(5);
    p.feed(frame.data(), 10);
    p.clear();
    CHECK(p.buffered() == 0);
    auto frames = parse_all(p, frame);
    REQUIRE(frames.size() == 1);
    CHECK(frames[0].ticks() == 5);
}
