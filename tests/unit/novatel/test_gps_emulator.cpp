// The receiver emulator's logic (tools/sim/gps), without a pty.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "capture_file.hpp"
#include "ugv/novatel/decoder.hpp"
#include "ugv/novatel/enums.hpp"
#include "ugv/sim/gps_emulator.hpp"

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

TEST_CASE("parse_script rejects unknown position types")
{
    CHECK_THROWS_AS(parse_script("SINGLE@0,BOGUS@3"), std::invalid_argument);
    const auto s = parse_script("NARROW_INT@5,SINGLE@0");
    REQUIRE(s.size() == 2);
    CHECK(s[0].position_type == position_type::single);
    CHECK(s[1].at_s == 5.0);
}
