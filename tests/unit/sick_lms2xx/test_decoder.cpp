// The streaming decoder: any split of a stream gives the same events; garbage and corrupted
// frames never produce a telegram, and the next good frame is always found.
#include <catch2/catch.hpp>

#include <random>
#include <vector>

#include "ugv/sick_lms2xx/crc.hpp"
#include "ugv/sick_lms2xx/decoder.hpp"
#include "ugv/sick_lms2xx/scan.hpp"
#include "ugv/sick_lms2xx/telegram.hpp"

using namespace ugv::sick_lms2xx;
using Bytes = std::vector<uint8_t>;

namespace {

struct Recorded
{
    std::vector<DecoderEvent::Kind> kinds;
    std::vector<Bytes> telegrams;  // raw bytes of each good telegram
};

Recorded decode(Decoder& dec, const Bytes& stream, const std::vector<std::size_t>& cuts)
{
    Recorded r;
    const auto handler = [&r](const DecoderEvent& ev) {
        r.kinds.push_back(ev.kind);
        if (ev.kind == DecoderEvent::Kind::telegram) r.telegrams.emplace_back(ev.telegram.raw.begin(), ev.telegram.raw.end());
    };
    std::size_t at = 0;
    for (const std::size_t cut : cuts) {
        dec.feed(stream.data() + at, cut - at, handler);
        at = cut;
    }
    dec.feed(stream.data() + at, stream.size() - at, handler);
    return r;
}

Bytes scan_frame(int seed, std::size_t n = 361)
{
    std::vector<uint16_t> values(n);
    for (std::size_t i = 0; i < n; ++i) values[i] = static_cast<uint16_t>((i * 37 + static_cast<std::size_t>(seed) * 101) % 8000);
    return encode_scan_telegram(values, Units::mm, 0, -1, 0x10);
}

// What a device sends after a request and while streaming: ACK, a mode reply, scans.
Bytes recorded_session_stream()
{
    Bytes s;
    const Bytes ok = {0x00};
    s.push_back(kAck);
    const Bytes a0 = encode_reply(0xA0, ok, 0x10);
    s.insert(s.end(), a0.begin(), a0.end());
    s.push_back(kNak);
    for (int i = 0; i < 3; ++i) {
        const Bytes f = scan_frame(i, 181);
        s.insert(s.end(), f.begin(), f.end());
    }
    return s;
}

}  // namespace

TEST_CASE("decoder reports ACK, NAK and telegrams in order", "[sick_lms2xx][decoder]")
{
    Decoder dec;
    const Bytes stream = recorded_session_stream();
    const Recorded r = decode(dec, stream, {});
    using K = DecoderEvent::Kind;
    REQUIRE(r.kinds == std::vector<K>{K::ack, K::telegram, K::nak, K::telegram, K::telegram, K::telegram});
    CHECK(r.telegrams[0] == encode_reply(0xA0, Bytes{0x00}, 0x10));
    CHECK(r.telegrams[1] == scan_frame(0, 181));
    CHECK(dec.stats().telegrams == 4);
    CHECK(dec.stats().crc_errors == 0);
    CHECK(dec.stats().resyncs == 0);
    CHECK(dec.stats().bytes_in == stream.size());
    CHECK(dec.buffered() == 0);
}

TEST_CASE("decoder gives the same events for a stream split at every byte position", "[sick_lms2xx][decoder]")
{
    const Bytes stream = recorded_session_stream();
    Decoder whole_dec;
    const Recorded whole = decode(whole_dec, stream, {});
    for (std::size_t cut = 1; cut < stream.size(); ++cut) {
        Decoder dec;
        const Recorded r = decode(dec, stream, {cut});
        REQUIRE(r.kinds == whole.kinds);
        REQUIRE(r.telegrams == whole.telegrams);
    }
    // And one byte at a time.
    std::vector<std::size_t> every;
    for (std::size_t i = 1; i < stream.size(); ++i) every.push_back(i);
    Decoder dec;
    const Recorded r = decode(dec, stream, every);
    CHECK(r.kinds == whole.kinds);
    CHECK(r.telegrams == whole.telegrams);
}

TEST_CASE("decoder fields of a reply telegram", "[sick_lms2xx][decoder]")
{
    const Bytes data = {0x01, 0xB4, 0x00, 0x32, 0x00};
    const Bytes frame = encode_reply(0xBB, data, 0x10);
    Decoder dec;
    int seen = 0;
    dec.feed(frame.data(), frame.size(), [&](const DecoderEvent& ev) {
        REQUIRE(ev.kind == DecoderEvent::Kind::telegram);
        CHECK(ev.telegram.address == 0x80);
        CHECK(ev.telegram.command == 0xBB);
        CHECK(Bytes(ev.telegram.data.begin(), ev.telegram.data.end()) == data);
        CHECK(ev.telegram.has_status);
        CHECK(ev.telegram.status == 0x10);
        ++seen;
    });
    CHECK(seen == 1);
}

TEST_CASE("decoder on the device side accepts requests (ADDR 0x00, no status)", "[sick_lms2xx][decoder]")
{
    Decoder dec(kHostAddress);
    const Bytes req = {0x02, 0x00, 0x05, 0x00, 0x3B, 0xB4, 0x00, 0x32, 0x00, 0x3B, 0x1F};
    int seen = 0;
    dec.feed(req.data(), req.size(), [&](const DecoderEvent& ev) {
        REQUIRE(ev.kind == DecoderEvent::Kind::telegram);
        CHECK(ev.telegram.command == 0x3B);
        CHECK_FALSE(ev.telegram.has_status);
        CHECK(ev.telegram.data.size() == 4);
        ++seen;
    });
    CHECK(seen == 1);
    // A reply (ADDR 0x80) is not a request: skipped.
    const Bytes reply = encode_reply(0xA0, Bytes{0x00}, 0);
    dec.feed(reply.data(), reply.size(), [&](const DecoderEvent&) { ++seen; });
    CHECK(seen == 1);
}

TEST_CASE("garbage between frames: every good frame decoded, nothing else", "[sick_lms2xx][decoder]")
{
    std::mt19937 rng(1234);
    std::uniform_int_distribution<int> byte(0, 255);
    std::uniform_int_distribution<int> glen(0, 60);
    Bytes stream;
    std::vector<Bytes> good;
    for (int i = 0; i < 200; ++i) {
        const int n = glen(rng);
        for (int k = 0; k < n; ++k) stream.push_back(static_cast<uint8_t>(byte(rng)));
        // Sometimes a false start: STX + ADDR + a plausible length, then nothing of the sort.
        if (i % 7 == 0) {
            const Bytes fake = {0x02, 0x80, 0x10, 0x00, 0xB0, 0x01};
            stream.insert(stream.end(), fake.begin(), fake.end());
        }
        const Bytes f = scan_frame(i, static_cast<std::size_t>(1 + i % 361));
        good.push_back(f);
        stream.insert(stream.end(), f.begin(), f.end());
    }
    // Enough trailing good frames that a fake header near the end cannot hide the last ones.
    for (int i = 0; i < 2; ++i) {
        const Bytes f = scan_frame(1000 + i);
        good.push_back(f);
        stream.insert(stream.end(), f.begin(), f.end());
    }
    for (const std::size_t chunk : {std::size_t{1}, std::size_t{7}, std::size_t{64}, std::size_t{4096}}) {
        Decoder dec;
        std::vector<std::size_t> cuts;
        for (std::size_t c = chunk; c < stream.size(); c += chunk) cuts.push_back(c);
        const Recorded r = decode(dec, stream, cuts);
        // No garbage may have formed a telegram that is not one of ours, in order.
        REQUIRE(r.telegrams == good);
        CHECK(dec.stats().resyncs > 0);
    }
}

TEST_CASE("a bit flip anywhere in a frame: the frame is dropped, the next one decoded", "[sick_lms2xx][decoder]")
{
    const Bytes victim = scan_frame(7, 40);
    const Bytes next = scan_frame(8, 361);
    for (std::size_t pos = 0; pos < victim.size(); ++pos) {
        for (int bit = 0; bit < 8; ++bit) {
            Bytes stream = victim;
            stream[pos] = static_cast<uint8_t>(stream[pos] ^ (1u << bit));
            // Two full-size frames behind it, so a corrupted LEN (up to 812) is always covered.
            for (int k = 0; k < 2; ++k) stream.insert(stream.end(), next.begin(), next.end());
            Decoder dec;
            const Recorded r = decode(dec, stream, {});
            INFO("pos " << pos << " bit " << bit);
            REQUIRE(r.telegrams == std::vector<Bytes>{next, next});
        }
    }
}

TEST_CASE("bad CRC is reported as bad_crc and counted", "[sick_lms2xx][decoder]")
{
    Bytes frame = encode_reply(0xA0, Bytes{0x00}, 0x10);
    frame.back() ^= 0xFF;
    Decoder dec;
    int bad = 0, good = 0;
    dec.feed(frame.data(), frame.size(), [&](const DecoderEvent& ev) {
        if (ev.kind == DecoderEvent::Kind::bad_crc) ++bad;
        if (ev.kind == DecoderEvent::Kind::telegram) ++good;
    });
    CHECK(bad == 1);
    CHECK(good == 0);
    CHECK(dec.stats().crc_errors == 1);
}

TEST_CASE("LEN above 812 is garbage even with a matching CRC", "[sick_lms2xx][decoder]")
{
    Bytes frame = {0x02, 0x80, 0x2D, 0x03, 0xB0};  // LEN 813
    frame.resize(4 + 813, 0x00);
    const uint16_t crc = crc16(frame.data(), frame.size());
    put_u16le(frame, crc);
    const Bytes good = encode_reply(0xA0, Bytes{0x00}, 0x10);
    frame.insert(frame.end(), good.begin(), good.end());
    Decoder dec;
    const Recorded r = decode(dec, frame, {});
    CHECK(r.telegrams == std::vector<Bytes>{good});
    CHECK(dec.stats().length_errors == 1);
    // LEN 0 likewise.
    Decoder dec0;
    Bytes zero = {0x02, 0x80, 0x00, 0x00};
    zero.insert(zero.end(), good.begin(), good.end());
    CHECK(decode(dec0, zero, {}).telegrams == std::vector<Bytes>{good});
    CHECK(dec0.stats().length_errors == 1);
}

TEST_CASE("reset forgets a partial frame", "[sick_lms2xx][decoder]")
{
    const Bytes good = encode_reply(0xA0, Bytes{0x00}, 0x10);
    Decoder dec;
    dec.feed(good.data(), 5, [](const DecoderEvent&) {});
    CHECK(dec.buffered() == 5);
    dec.reset();
    CHECK(dec.buffered() == 0);
    CHECK(decode(dec, good, {}).telegrams == std::vector<Bytes>{good});
}
