// Every frame of the real NovAtel and NMEA captures (../shared/data/real, README.md there)
// is found with a valid checksum, and the counts are the README's.
#include <catch2/catch.hpp>

#include <map>
#include <string>

#include "capture_file.hpp"
#include "ugv/novatel/decoder.hpp"

using namespace ugv::novatel;
using ugv::novatel::test::read_capture;

namespace {

struct Tally
{
    SplitterCounters counters;
    std::map<uint16_t, int> binary_ids;        // long-header frames by message id
    std::map<std::string, int> text_names;     // ASCII logs and NMEA sentences by name
    std::size_t buffered = 0;
};

Tally tally(const std::string& file)
{
    const auto data = read_capture(file);
    StreamSplitter s;
    Tally t;
    s.feed(data.data(), data.size(), [&](const FrameView& f) {
        if (f.kind == FrameKind::binary) {
            ++t.binary_ids[static_cast<uint16_t>(f.data[4] | f.data[5] << 8)];
        } else if (f.kind == FrameKind::ascii || f.kind == FrameKind::ascii_short || f.kind == FrameKind::nmea) {
            const std::string text(reinterpret_cast<const char*>(f.data), f.size);
            ++t.text_names[text.substr(0, text.find_first_of(",;"))];
        }
    });
    t.counters = s.counters();
    t.buffered = s.buffered();
    return t;
}

uint64_t frames(const Tally& t, FrameKind k) { return t.counters.frames[static_cast<std::size_t>(k)]; }

}  // namespace

TEST_CASE("real: swri bestpos-bestvel-psrdop2 (OEM6 over TCP): 33 BESTPOSB, 33 BESTVELB, 33 PSRDOP2B")
{
    const auto t = tally("swri-novatel_gps_driver/bestpos-bestvel-psrdop2-sync.tcp-payload.bin");
    CHECK(frames(t, FrameKind::binary) == 99);
    CHECK(t.binary_ids.at(42) == 33);
    CHECK(t.binary_ids.at(99) == 33);
    CHECK(t.binary_ids.at(1163) == 33);
    CHECK(frames(t, FrameKind::prompt) == 1);  // [ICOM1]
    CHECK(t.counters.crc_errors == 0);
    CHECK(t.counters.skipped_bytes == 0);
    CHECK(t.buffered == 0);
}

TEST_CASE("real: swri corrimudata (SPAN): 89 binary frames after <OK [ICOM1] replies")
{
    const auto t = tally("swri-novatel_gps_driver/corrimudata.tcp-payload.bin");
    CHECK(frames(t, FrameKind::binary) == 89);
    CHECK(t.binary_ids.at(812) == 29);
    CHECK(t.binary_ids.at(1465) == 28);
    CHECK(t.binary_ids.at(42) == 28);
    CHECK(t.binary_ids.at(101) == 2);
    CHECK(t.binary_ids.at(264) == 2);
    CHECK(t.counters.crc_errors == 0);
    CHECK(t.counters.skipped_bytes == 0);
}

TEST_CASE("real: swri gpgga-gprmc-bestpos: NovAtel ASCII and NMEA interleaved from one receiver")
{
    const auto t = tally("swri-novatel_gps_driver/gpgga-gprmc-bestpos.udp-payload.bin");
    CHECK(t.text_names.at("#BESTPOSA") == 40);
    CHECK(t.text_names.at("#TIMEA") == 2);
    CHECK(t.text_names.at("$GPGGA") == 40);
    CHECK(t.text_names.at("$GPRMC") == 40);
    CHECK(frames(t, FrameKind::ascii) == 42);
    CHECK(frames(t, FrameKind::nmea) == 80);
    CHECK(t.counters.crc_errors == 0);
    CHECK(t.counters.skipped_bytes == 0);
}

TEST_CASE("real: ProPak6 SPAN stream: 3904 binary frames and 636+ command replies")
{
    const auto t = tally("ros-drivers-novatel_span_driver/propak6-sbas-fix.tcp-payload.bin");
    CHECK(frames(t, FrameKind::binary) == 3904);
    CHECK(t.binary_ids.at(42) == 1280);
    CHECK(t.binary_ids.at(812) == 1280);
    CHECK(t.binary_ids.at(1465) == 1280);
    CHECK(t.binary_ids.at(264) == 64);
    CHECK(frames(t, FrameKind::reply) >= 636);
    CHECK(t.counters.crc_errors == 0);
    CHECK(t.counters.skipped_bytes == 0);
}

TEST_CASE("real: novatel_edie resources")
{
    auto t = tally("novatel_edie/bestpos.bin");
    CHECK(t.binary_ids.at(42) == 3);
    CHECK(frames(t, FrameKind::binary) == 3);
    t = tally("novatel_edie/bestpos.asc");
    CHECK(t.text_names.at("#BESTPOSA") == 3);
    t = tally("novatel_edie/BESTUTMBIN.GPS");
    CHECK(t.binary_ids.at(726) == 1);
    CHECK(t.text_names.at("#BESTUTMA") == 1);
    CHECK(t.text_names.at("#VERSIONA") == 1);
    t = tally("novatel_edie/advancedecoder_version.bin");
    CHECK(t.binary_ids.at(37) == 1);
    t = tally("novatel_edie/rawimusx.BIN");
    CHECK(frames(t, FrameKind::binary_short) == 1);
    t = tally("novatel_edie/rawimusx.ASC");
    CHECK(t.text_names.at("%RAWIMUSXA") == 1);
    CHECK(t.counters.crc_errors == 0);
}

TEST_CASE("real: the LF->CRLF damaged all-logs dump: 549 long + 14 short frames survive, no stall")
{
    const auto t = tally("novatel_edie/advanceddecoder_alllogs.BIN");
    CHECK(frames(t, FrameKind::binary) == 549);
    CHECK(frames(t, FrameKind::binary_short) == 14);
    // The damaged frames fail their CRC (the README counts 109 bad headers; one of them is
    // rejected earlier by its out-of-bounds length field).
    CHECK(t.counters.crc_errors + t.counters.bad_length == 109);
    CHECK(t.binary_ids.size() >= 200);
}

TEST_CASE("real: GAVLab OEMV/OEM4 serial captures (.GPS binary + #SENDR, .ASC twins)")
{
    struct Expect
    {
        const char* file;
        uint64_t binary;
        uint64_t ascii;
    };
    const Expect files[] = {
        {"gavlab-novatel/ParsingData.GPS", 288, 0},    {"gavlab-novatel/ParsingData.ASC", 0, 265},
        {"gavlab-novatel/ParsingData2.GPS", 67, 0},    {"gavlab-novatel/ParsingData2.ASC", 0, 63},
        {"gavlab-novatel/OneEach.GPS", 8, 7},          {"gavlab-novatel/OneEach.ASC", 0, 15},
        {"gavlab-novatel/OnceEachAgain.GPS", 49, 9},   {"gavlab-novatel/OnceEachAgain.ASC", 0, 58},
        {"gavlab-novatel/MorePropak.GPS", 5, 9},       {"gavlab-novatel/MorePropak.ASC", 0, 14},
        {"gavlab-novatel/PropakWithGlonass.GPS", 26, 13}, {"gavlab-novatel/PropakWithGlonass.ASC", 0, 39},
        {"gavlab-novatel/ascii_version_test_data_oem4_span.log", 0, 1},
        {"gavlab-novatel/ascii_version_test_data_oem5_propak3_glonass.log", 0, 1},
        {"gavlab-novatel/ascii_version_test_data_oem5_dlv3.log", 0, 0},
    };
    for (const auto& e : files) {
        INFO(e.file);
        const auto t = tally(e.file);
        CHECK(frames(t, FrameKind::binary) == e.binary);
        CHECK(frames(t, FrameKind::ascii) == e.ascii);
        CHECK(t.counters.crc_errors == 0);
    }
    const auto p = tally("gavlab-novatel/ParsingData.GPS");
    CHECK(p.binary_ids.at(42) == 84);
    CHECK(p.binary_ids.at(83) == 83);
    CHECK(p.binary_ids.at(48) == 83);
    CHECK(p.binary_ids.at(1) == 17);  // LOG responses
    CHECK(p.binary_ids.at(36) == 6);  // UNLOG responses
    CHECK(p.binary_ids.at(99) == 1);
    CHECK(p.binary_ids.at(47) == 1);
    // ParsingData2.GPS ends in a truncated frame: it stays buffered, never handed out.
    CHECK(tally("gavlab-novatel/ParsingData2.GPS").buffered > 0);
}

TEST_CASE("real: RTKLIB OEMV log from receiver start-up, cut at 256 KiB")
{
    const auto t = tally("rtklib/oemv_200911218.gps");
    CHECK(frames(t, FrameKind::binary) == 317);
    CHECK(t.binary_ids.at(287) == 90);
    CHECK(t.binary_ids.at(83) == 50);
    CHECK(t.binary_ids.at(42) == 49);
    CHECK(t.binary_ids.at(48) == 49);
    CHECK(t.binary_ids.at(140) == 46);
    CHECK(t.binary_ids.at(41) == 25);
    CHECK(t.binary_ids.at(723) == 8);
    CHECK(t.counters.crc_errors == 0);
    CHECK(t.buffered > 0);  // the truncated last frame
}

TEST_CASE("real: gpsd NMEA regression logs, every sentence's checksum valid")
{
    struct Expect
    {
        const char* file;
        uint64_t sentences;
        const char* gst;
        int gst_count;
    };
    const Expect files[] = {
        {"gpsd-test-daemon/polarx2.log", 75, "$GPGST", 5},
        {"gpsd-test-daemon/ublox-lea-5q.log", 63, "$GPGST", 9},
        {"gpsd-test-daemon/skytraq-fix.log", 100, "$GPGST", 11},
        {"gpsd-test-daemon/gr8013-w.log", 48, "$GNGST", 3},
        {"gpsd-test-daemon/nmea-rtk.log", 244, "$GPGGA", 72},
    };
    for (const auto& e : files) {
        INFO(e.file);
        const auto t = tally(e.file);
        CHECK(frames(t, FrameKind::nmea) == e.sentences);
        CHECK(t.text_names.at(e.gst) == e.gst_count);
        CHECK(t.counters.crc_errors == 0);
    }
}

TEST_CASE("real: the decoder decodes every BESTPOS/BESTVEL/TIME/PSRPOS/PSRVEL and counts the rest by id")
{
    const auto data = read_capture("gavlab-novatel/OnceEachAgain.GPS");
    Decoder d;
    std::map<std::string, int> decoded;
    d.feed(data.data(), data.size(), 0, [&](const Decoded& m) {
        std::visit(
            [&](const auto& v) {
                using T = std::decay_t<decltype(v)>;
                if constexpr (std::is_same_v<T, Position>) {
                    decoded[v.header.id == log_id::bestpos ? "BESTPOS" : "PSRPOS"]++;
                } else if constexpr (std::is_same_v<T, Velocity>) {
                    decoded[v.header.id == log_id::bestvel ? "BESTVEL" : "PSRVEL"]++;
                } else if constexpr (std::is_same_v<T, Reply>) {
                    decoded["reply"]++;
                } else {
                    decoded["other"]++;
                }
            },
            m.message);
    });
    CHECK(decoded["BESTPOS"] == 1);
    CHECK(decoded["PSRPOS"] == 1);
    CHECK(decoded["BESTVEL"] == 1);
    CHECK(decoded["PSRVEL"] == 1);
    CHECK(d.counters().malformed == 0);
    CHECK(d.counters().unknown_binary_ids.at(7) == 38);  // GPSEPHEM
    CHECK(d.counters().unknown_binary_ids.at(43) == 1);  // RANGE
    CHECK(d.counters().unknown_names.at("SENDR") == 9);
}
