// The receiver emulator's logic (tools/sim/gps), without a pty.
#include <catch2/catch.hpp>

#include <cstdio>
#include <string>
#include <vector>

#include "capture_file.hpp"
#include "gps_emulator.hpp"
#include "ugv/novatel/checksum.hpp"
#include "ugv/novatel/decoder.hpp"
#include "ugv/novatel/enums.hpp"

using namespace ugv::sim::gps;
using namespace ugv::novatel;
using ugv::novatel::test::bytes;

namespace {

constexpr int64_t kStart = 1'700'000'000'000'000LL;  // on a whole second, GPS and UTC alike

std::string send(GpsEmulator& e, const std::string& text)
{
    const auto b = bytes(text);
    return e.on_host_bytes(b.data(), b.size());
}

std::vector<Position> positions(const std::string& out)
{
    Decoder d;
    std::vector<Position> p;
    const auto b = bytes(out);
    d.feed(b.data(), b.size(), 0, [&](const Decoded& m) {
        if (const auto* x = std::get_if<Position>(&m.message)) p.push_back(*x);
    });
    return p;
}

}  // namespace

TEST_CASE("emulator: answers UNLOGALL/LOG/COM with <OK and a prompt, unknown ones with <ERROR")
{
    GpsEmulator e(EmulatorConfig{}, kStart);
    CHECK(send(e, "UNLOGALL\r\n") == "\r\n<OK\r\n[COM1]");
    CHECK(send(e, "log com1 bestposb ontime 0.5\r\n") == "\r\n<OK\r\n[COM1]");
    CHECK(e.active_logs() == 1);
    CHECK(send(e, "LOG RANGEB ONTIME 1\r\n").find("<ERROR:") != std::string::npos);
    CHECK(send(e, "LOG BESTVELB ONCE\r\n").find("<ERROR:") != std::string::npos);
    CHECK(send(e, "FRESET\r\n").find("<ERROR:") != std::string::npos);
    CHECK(send(e, "COM 115200\r\n") == "\r\n<OK\r\n[COM1]");
    CHECK(e.baud() == 115200);
    // A command split over several writes.
    CHECK(send(e, "UNLO").empty());
    CHECK(send(e, "GALL\r\n") == "\r\n<OK\r\n[COM1]");
    CHECK(e.active_logs() == 0);
    CHECK(e.commands_received() == 7);
}

TEST_CASE("emulator: ONTIME logs come on multiples of the period, with the scripted position types")
{
    EmulatorConfig c;
    c.noise_scale = 0;
    c.script = parse_script("SINGLE@0,PSRDIFF@1,NARROW_INT@2");
    GpsEmulator e(c, kStart);
    send(e, "LOG BESTPOSB ONTIME 0.25\r\n");
    std::string out;
    for (int64_t t = kStart; t <= kStart + 3'000'000; t += 10'000) {
        out += e.tick(t);
    }
    const auto p = positions(out);
    REQUIRE(p.size() == 12);  // 0.25, 0.5, ... 3.0 s
    for (std::size_t i = 0; i < p.size(); ++i) {
        CHECK(p[i].header.ms % 250 == 0);
        CHECK(p[i].header.time_status == time_status::finesteering);
        CHECK(p[i].latitude_deg == Approx(c.latitude_deg).margin(1e-12));
    }
    // p[i] is at (i + 1) * 0.25 s.
    CHECK(p[0].position_type == position_type::single);
    CHECK(p[2].position_type == position_type::single);      // 0.75 s
    CHECK(p[3].position_type == position_type::psrdiff);     // 1.0 s
    CHECK(p[6].position_type == position_type::psrdiff);     // 1.75 s
    CHECK(p[7].position_type == position_type::narrow_int);  // 2.0 s
    CHECK(p[11].sigma_latitude_m == Approx(0.02));
}

TEST_CASE("emulator: a straight line moves the truth at the configured speed and heading")
{
    EmulatorConfig c;
    c.speed_mps = 10.0;
    c.heading_deg = 0.0;
    GpsEmulator e(c, kStart);
    double lat = 0, lon = 0;
    e.truth(kStart + 10'000'000, lat, lon);
    // 100 m north: 100 / 6378137 rad.
    CHECK(lat - c.latitude_deg == Approx(100.0 / 6378137.0 * 180.0 / 3.141592653589793).epsilon(1e-9));
    CHECK(lon == c.longitude_deg);
}

TEST_CASE("emulator: preconfigured NMEA output, silence and garbage faults")
{
    EmulatorConfig c;
    c.protocol = Protocol::nmea;
    c.preconfigured = true;
    c.rate_hz = 4;
    c.silence_at_s = 1.0;
    c.silence_for_s = 1.0;
    c.garbage_period_s = 0.5;
    GpsEmulator e(c, kStart);
    std::string first, silent;
    for (int64_t t = kStart; t < kStart + 1'000'000; t += 10'000) first += e.tick(t);
    for (int64_t t = kStart + 1'000'000; t < kStart + 2'000'000; t += 10'000) silent += e.tick(t);
    Decoder d;
    int gga = 0, rmc = 0, gst = 0;
    const auto b = bytes(first);
    d.feed(b.data(), b.size(), 0, [&](const Decoded& m) {
        gga += std::holds_alternative<Gga>(m.message);
        rmc += std::holds_alternative<Rmc>(m.message);
        gst += std::holds_alternative<Gst>(m.message);
    });
    CHECK(gga == 3);  // 0.25, 0.5, 0.75 s
    CHECK(rmc == 3);
    CHECK(gst == 3);
    CHECK(d.splitter_counters().skipped_bytes > 0);  // the garbage burst at 0.5 s
    CHECK(silent.size() == 2 * 40);                  // only garbage while silent
}

namespace {

// 10 s of a preconfigured NovAtel receiver (BESTPOSB + BESTVELB at 20 Hz, no noise).
EmulatorConfig binary_20hz()
{
    EmulatorConfig c;
    c.preconfigured = true;
    c.rate_hz = 20;
    c.noise_scale = 0;
    c.seed = 3;
    return c;
}

uint64_t pos_and_vel_frames(Decoder& d, const std::string& out)
{
    uint64_t n = 0;
    const auto b = bytes(out);
    d.feed(b.data(), b.size(), 0, [&](const Decoded& m) {
        n += std::holds_alternative<Position>(m.message) || std::holds_alternative<Velocity>(m.message);
    });
    return n;
}

std::string ten_seconds(GpsEmulator& e)
{
    std::string out;
    for (int64_t t = kStart; t < kStart + 10'000'000; t += 10'000) out += e.tick(t);
    return out;
}

}  // namespace

TEST_CASE("emulator: bit errors per byte damage that share of bytes; every frame that still decodes is exact")
{
    for (const double rate : {1e-3, 1e-2}) {
        INFO("rate " << rate);
        EmulatorConfig c = binary_20hz();
        c.bit_error_rate = rate;
        GpsEmulator e(c, kStart);
        const std::string out = ten_seconds(e);
        // 200 BESTPOSB (104 bytes) + 200 BESTVELB (76 bytes).
        const double share = static_cast<double>(e.bytes_damaged()) / static_cast<double>(out.size());
        CHECK(share > 0.6 * rate);
        CHECK(share < 1.4 * rate);
        Decoder d;
        std::size_t fixes = 0;
        const auto b = bytes(out);
        d.feed(b.data(), b.size(), 0, [&](const Decoded& m) {
            const auto* p = std::get_if<Position>(&m.message);
            if (p == nullptr) return;
            ++fixes;
            REQUIRE(p->latitude_deg == c.latitude_deg);
            REQUIRE(p->longitude_deg == c.longitude_deg);
            REQUIRE(p->height_msl_m == c.height_msl_m);
        });
        CHECK(d.splitter_counters().crc_errors > 0);
        // 104 bytes survive 1e-3 with p = 0.90 and 1e-2 with p = 0.35.
        const std::size_t expected = rate == 1e-3 ? 180 : 70;
        CHECK(fixes > expected * 7 / 10);
        CHECK(fixes < expected * 13 / 10);
    }
    // A reply is damaged too: with every byte hit, "<OK" no longer reads as one.
    EmulatorConfig c;
    c.bit_error_rate = 1.0;
    GpsEmulator e(c, kStart);
    CHECK(send(e, "UNLOGALL\r\n").find("<OK") == std::string::npos);
    CHECK(e.bytes_damaged() > 0);
}

TEST_CASE("emulator: truncated frames never decode, and the frame after each one does")
{
    EmulatorConfig c = binary_20hz();
    c.truncate_probability = 0.2;
    GpsEmulator e(c, kStart);
    const std::string out = ten_seconds(e);
    const uint64_t cut = e.frames_truncated();
    CHECK(cut > 40);
    CHECK(cut < 120);
    Decoder d;
    const uint64_t frames = pos_and_vel_frames(d, out);
    GpsEmulator clean(binary_20hz(), kStart);
    Decoder d_clean;
    const uint64_t sent = pos_and_vel_frames(d_clean, ten_seconds(clean));
    CHECK(sent >= 396);  // 20 Hz x 2 logs x 10 s, less the first period
    CHECK(frames + cut >= sent - 1);  // the last cut frame may still wait for its claimed length
    CHECK(frames + cut <= sent);
    // A cut frame fails its CRC once its claimed length has arrived (or breaks the sync or
    // the length when cut inside them) and is skipped; cut frames in a row skip as one run.
    CHECK(d.splitter_counters().crc_errors > cut / 2);
    CHECK(d.splitter_counters().resyncs > cut / 2);
}

TEST_CASE("parse_script rejects unknown position types")
{
    CHECK_THROWS_AS(parse_script("SINGLE@0,BOGUS@3"), std::invalid_argument);
    const auto s = parse_script("NARROW_INT@5,SINGLE@0");
    REQUIRE(s.size() == 2);
    CHECK(s[0].position_type == position_type::single);
    CHECK(s[1].at_s == 5.0);
}

TEST_CASE("Emulator: damaged NMEA sentences whose checksum still holds are counted as unseen")
{
    const auto sentence = [](const std::string& body) {
        char sum[8];
        std::snprintf(sum, sizeof sum, "*%02X\r\n",
                      ugv::novatel::nmea_checksum(reinterpret_cast<const uint8_t*>(body.data()), body.size()));
        return "$" + body + sum;
    };
    const std::string sent = sentence("GPGGA,120000.00,4807.038,N,01131.000,E,1,08,0.9,545.4,M,46.9,M,,") +
                             sentence("GPGST,120000.00,1.0,0.5,0.3,45.0,0.5,0.4,0.8");
    CHECK(ugv::sim::gps::count_nmea_damage_unseen(sent, sent) == 0);
    std::string one_flip = sent;
    one_flip[20] ^= 0x01;  // a digit of the latitude: the checksum no longer holds
    CHECK(ugv::sim::gps::count_nmea_damage_unseen(sent, one_flip) == 0);
    std::string two_flips = sent;
    two_flips[20] ^= 0x01;  // the same bit in two bytes of one sentence: the XOR is unchanged
    two_flips[30] ^= 0x01;
    CHECK(ugv::sim::gps::count_nmea_damage_unseen(sent, two_flips) == 1);
    std::string framing = two_flips;
    framing[0] ^= 0x04;  // '$' -> ' ': the host does not see this sentence at all
    CHECK(ugv::sim::gps::count_nmea_damage_unseen(sent, framing) == 0);
}
