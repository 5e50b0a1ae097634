#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "capture_file.hpp"
#include "ugv/novatel/encoding.hpp"
#include "ugv/novatel/stream_splitter.hpp"

using namespace ugv::novatel;
using ugv::novatel::test::bytes;

namespace {

struct Seen
{
    FrameKind kind;
    std::string bytes;
    uint64_t end_offset;
};

std::vector<Seen> split(StreamSplitter& s, const std::vector<uint8_t>& data, std::size_t chunk)
{
    std::vector<Seen> out;
    for (std::size_t i = 0; i < data.size(); i += chunk) {
        const std::size_t n = std::min(chunk, data.size() - i);
        s.feed(data.data() + i, n, [&](const FrameView& f) {
            out.push_back({f.kind, std::string(reinterpret_cast<const char*>(f.data), f.size), f.end_offset});
        });
    }
    return out;
}

std::vector<uint8_t> binary_bestpos(uint32_t ms)
{
    Position p;
    p.header.id = log_id::bestpos;
    p.header.time_status = 180;
    p.header.week = 2080;
    p.header.ms = ms;
    p.position_type = 16;
    p.latitude_deg = 29.4439;
    p.longitude_deg = -98.6147;
    p.height_msl_m = 259.5;
    p.undulation_m = -26.0;
    return encode_binary(p.header, encode_position_body(p));
}

// A port as receivers really fill it: a prompt, a reply, a binary log, an ASCII log, NMEA.
std::vector<uint8_t> mixed_stream()
{
    std::vector<uint8_t> s = bytes("[COM1]<OK\r\n");
    const auto bin = binary_bestpos(412623400);
    s.insert(s.end(), bin.begin(), bin.end());
    const auto ascii = bytes(
        "#BESTPOSA,COM1,0,65.5,FINESTEERING,1687,419928.000,00000000,6145,3153;SOL_COMPUTED,SINGLE,32.59535912622,"
        "-85.29567789741,199.9777,-29.2000,WGS84,1.1396,1.1687,2.4308,\"\",0.000,0.000,12,12,0,0,0,06,00,03*49329266"
        "\r\n");
    s.insert(s.end(), ascii.begin(), ascii.end());
    const auto nmea = bytes("$GPGGA,,,,,,0,,,,,,,,*66\r\n");
    s.insert(s.end(), nmea.begin(), nmea.end());
    const auto bin2 = binary_bestpos(412623650);
    s.insert(s.end(), bin2.begin(), bin2.end());
    const auto short_ascii = bytes(
        "%RAWIMUSXA,1692,484620.664;00,11,1692,484620.664389000,00801503,43110635,-817242,-202184,-215194,-41188,"
        "-9895*a5db8c7b\r\n");
    s.insert(s.end(), short_ascii.begin(), short_ascii.end());
    return s;
}

}  // namespace

TEST_CASE("splitter: binary, ASCII, short ASCII, NMEA, replies and prompts interleaved on one port")
{
    StreamSplitter s;
    const auto data = mixed_stream();
    const auto frames = split(s, data, data.size());
    REQUIRE(frames.size() == 7);
    CHECK(frames[0].kind == FrameKind::prompt);
    CHECK(frames[0].bytes == "[COM1]");
    CHECK(frames[1].kind == FrameKind::reply);
    CHECK(frames[1].bytes == "<OK");
    CHECK(frames[2].kind == FrameKind::binary);
    CHECK(frames[2].bytes.size() == 28 + 72 + 4);
    CHECK(frames[3].kind == FrameKind::ascii);
    CHECK(frames[3].bytes.substr(0, 9) == "#BESTPOSA");
    CHECK(frames[4].kind == FrameKind::nmea);
    CHECK(frames[4].bytes == "$GPGGA,,,,,,0,,,,,,,,*66");
    CHECK(frames[5].kind == FrameKind::binary);
    CHECK(frames[6].kind == FrameKind::ascii_short);
    CHECK(s.counters().skipped_bytes == 0);
    CHECK(s.counters().resyncs == 0);
    CHECK(s.counters().crc_errors == 0);
    CHECK(s.buffered() == 0);
    // end_offset points one past each frame's last byte in the stream.
    CHECK(frames[0].end_offset == 6);
    CHECK(frames[2].end_offset == 11 + 104);
}

TEST_CASE("splitter: the same frames whatever the split, two pieces at every byte and byte by byte")
{
    const auto data = mixed_stream();
    StreamSplitter whole_splitter;
    const auto whole = split(whole_splitter, data, data.size());
    for (std::size_t cut = 1; cut < data.size(); ++cut) {
        StreamSplitter s;
        std::vector<Seen> got;
        const auto sink = [&](const FrameView& f) {
            got.push_back({f.kind, std::string(reinterpret_cast<const char*>(f.data), f.size), f.end_offset});
        };
        s.feed(data.data(), cut, sink);
        s.feed(data.data() + cut, data.size() - cut, sink);
        REQUIRE(got.size() == whole.size());
        for (std::size_t i = 0; i < got.size(); ++i) {
            CHECK(got[i].bytes == whole[i].bytes);
            CHECK(got[i].end_offset == whole[i].end_offset);
        }
        CHECK(s.counters().skipped_bytes == 0);
    }
    StreamSplitter bytewise;
    const auto one = split(bytewise, data, 1);
    REQUIRE(one.size() == whole.size());
    for (std::size_t i = 0; i < one.size(); ++i) {
        CHECK(one[i].bytes == whole[i].bytes);
    }
}

TEST_CASE("splitter: garbage between frames is skipped and counted as one resync per run")
{
    std::vector<uint8_t> data = bytes("PING\r\nxx\x01\x02");
    const auto frame = binary_bestpos(1000);
    data.insert(data.end(), frame.begin(), frame.end());
    const auto junk = bytes("\xAA\x44\x99zz$GPGGA,no star\r\n");
    data.insert(data.end(), junk.begin(), junk.end());
    const auto nmea = bytes("$GPGGA,,,,,,0,,,,,,,,*66\r\n");
    data.insert(data.end(), nmea.begin(), nmea.end());
    StreamSplitter s;
    const auto frames = split(s, data, 7);
    REQUIRE(frames.size() == 2);
    CHECK(frames[0].kind == FrameKind::binary);
    CHECK(frames[1].kind == FrameKind::nmea);
    CHECK(s.counters().resyncs == 2);
    // "PING" + "xx\x01\x02" (the CR LF between are line ends, not garbage), then the junk run
    // less its final CR LF.
    CHECK(s.counters().skipped_bytes == 4 + 4 + (junk.size() - 2));
}

TEST_CASE("splitter: a corrupted body length does not stall: the next frames still come out")
{
    auto bad = binary_bestpos(1000);
    bad[8] = 0xFF;  // body length 0x48 -> 0xFF: beyond the frame, and the CRC cannot match
    bad[9] = 0x0F;  // 0x0FFF = 4095 bytes, just inside the bound: the worst case
    std::vector<uint8_t> data = bad;
    std::vector<uint8_t> good_frames;
    for (uint32_t i = 0; i < 60; ++i) {
        const auto f = binary_bestpos(2000 + i);
        good_frames.insert(good_frames.end(), f.begin(), f.end());
    }
    data.insert(data.end(), good_frames.begin(), good_frames.end());
    StreamSplitter s;
    const auto frames = split(s, data, 64);
    // The corrupt header waits at most for its bounded length (4127 bytes), then fails its
    // CRC and the splitter resynchronises on the frames inside that window.
    REQUIRE(frames.size() == 60);
    CHECK(s.counters().crc_errors == 1);
    CHECK(s.counters().resyncs == 1);
    CHECK(s.buffered() < 104);

    auto huge = binary_bestpos(1000);
    huge[9] = 0xF0;  // 61 kB: beyond the bound, rejected at once
    std::vector<uint8_t> data2 = huge;
    const auto next = binary_bestpos(3000);
    data2.insert(data2.end(), next.begin(), next.end());
    StreamSplitter s2;
    const auto frames2 = split(s2, data2, data2.size());
    REQUIRE(frames2.size() == 1);
    CHECK(s2.counters().bad_length == 1);
    CHECK(s2.buffered() == 0);
}

TEST_CASE("splitter: a bad checksum is counted and the frame never handed out")
{
    auto frame = binary_bestpos(1000);
    frame[40] ^= 0x01;
    std::vector<uint8_t> data = frame;
    const auto nmea = bytes("$GPGGA,,,,,,0,,,,,,,,*67\r\n$GPGGA,,,,,,0,,,,,,,,*66\r\n");
    data.insert(data.end(), nmea.begin(), nmea.end());
    StreamSplitter s;
    const auto frames = split(s, data, data.size());
    REQUIRE(frames.size() == 1);
    CHECK(frames[0].kind == FrameKind::nmea);
    CHECK(s.counters().crc_errors == 2);
}

TEST_CASE("splitter: a text frame broken by a line end or a binary byte is garbage, not a wait")
{
    const auto data = bytes("#BESTPOSA,COM1,0\r\n$GPGGA,\x01,\r\n$GPGGA,,,,,,0,,,,,,,,*66\r\n");
    StreamSplitter s;
    const auto frames = split(s, data, 3);
    REQUIRE(frames.size() == 1);
    CHECK(frames[0].bytes == "$GPGGA,,,,,,0,,,,,,,,*66");
    CHECK(s.buffered() == 0);
}

TEST_CASE("splitter: reset forgets a partial frame")
{
    const auto frame = binary_bestpos(1000);
    StreamSplitter s;
    int n = 0;
    s.feed(frame.data(), 50, [&](const FrameView&) { ++n; });
    CHECK(s.buffered() == 50);
    s.reset();
    CHECK(s.buffered() == 0);
    s.feed(frame.data(), frame.size(), [&](const FrameView&) { ++n; });
    CHECK(n == 1);
}
