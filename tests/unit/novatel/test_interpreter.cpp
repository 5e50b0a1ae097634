#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include "capture_file.hpp"
#include "ugv/novatel/decoder.hpp"
#include "ugv/novatel/enums.hpp"
#include "ugv/novatel/interpreter.hpp"

using namespace ugv::novatel;
using Catch::Matchers::WithinAbs;
using ugv::novatel::test::read_capture;

namespace {

Position bestpos(uint32_t time_status, uint32_t ms)
{
    Position p;
    p.header.kind = FrameKind::binary;
    p.header.id = log_id::bestpos;
    p.header.time_status = time_status;
    p.header.week = 2080;
    p.header.ms = ms;
    p.solution_status = solution_status::sol_computed;
    p.position_type = position_type::narrow_int;
    p.latitude_deg = 45.0;
    p.longitude_deg = -75.0;
    p.height_msl_m = 100.0;
    p.undulation_m = -34.5;
    p.sigma_latitude_m = 0.01;
    p.sigma_longitude_m = 0.02;
    p.sigma_height_m = 0.03;
    p.differential_age_s = 1.5;
    p.satellites_tracked = 14;
    p.satellites_used = 11;
    return p;
}

Gga gga(double utc_s, int quality)
{
    Gga g;
    g.talker = "GP";
    g.utc_time_s = utc_s;
    g.quality = quality;
    g.latitude_deg = 45.0;
    g.longitude_deg = -75.0;
    g.altitude_msl_m = 100.0;
    g.undulation_m = -34.5;
    g.satellites_used = 9;
    g.differential_age_s = 3.0;
    return g;
}

Gst gst(double utc_s)
{
    Gst g;
    g.talker = "GP";
    g.utc_time_s = utc_s;
    g.sigma_latitude_m = 0.5;
    g.sigma_longitude_m = 0.6;
    g.sigma_altitude_m = 0.9;
    return g;
}

// 2019-11-21T00:00:00Z, the day of GPS week 2080 ms 412623400 (18:36:45.4 UTC).
constexpr int64_t kDay = 1574294400LL * 1'000'000;
constexpr int64_t kMeasured = 1574361405'400'000LL;

}  // namespace

TEST_CASE("interpreter: FINESTEERING BESTPOS is stamped with GPS time converted to UTC")
{
    Interpreter in;
    const int64_t arrival = kMeasured + 65'000;
    const auto out = in.on_message(bestpos(time_status::finesteering, 412623400), FrameKind::binary, arrival, 104);
    REQUIRE(out.fix);
    const Fix& f = *out.fix;
    CHECK(f.utime == kMeasured);
    CHECK(f.time_from_receiver);
    CHECK(f.gps_week == 2080);
    CHECK(f.gps_ms == 412623400);
    CHECK(f.height_m == 100.0 - 34.5);
    CHECK(f.undulation_m == -34.5);
    CHECK(f.quality == FixQuality::rtk_fixed);
    CHECK(f.position_type == 50);
    CHECK(f.solution_status == 0);
    CHECK(f.sigma_longitude_m == 0.02);
    CHECK(f.differential_age_s == 1.5);
    CHECK(f.satellites_used == 11);
    CHECK(f.satellites_tracked == 14);
    CHECK(f.source == Source::novatel_binary);
    CHECK(in.clock().last_us() == 65'000);
    CHECK(in.last_time_status() == time_status::finesteering);
}

TEST_CASE("interpreter: leap seconds are configurable")
{
    InterpreterConfig cfg;
    cfg.leap_seconds = 17;
    Interpreter in(cfg);
    const auto out = in.on_message(bestpos(time_status::fine, 412623400), FrameKind::binary, kMeasured, 104);
    REQUIRE(out.fix);
    CHECK(out.fix->utime == kMeasured + 1'000'000);
}

TEST_CASE("interpreter: before FINE, the stamp is arrival minus transmission and output latency")
{
    InterpreterConfig cfg;
    cfg.output_latency_us = 20'000;
    cfg.baud = 115200;
    Interpreter in(cfg);
    const int64_t arrival = 1'700'000'000'000'000LL;
    const auto out = in.on_message(bestpos(time_status::coarsesteering, 412623400), FrameKind::binary, arrival, 104);
    REQUIRE(out.fix);
    // 104 bytes * 10 bits / 115200 baud = 9.028 ms
    CHECK(out.fix->utime == arrival - 20'000 - 9'028);
    CHECK_FALSE(out.fix->time_from_receiver);
    CHECK(out.fix->gps_week == 2080);  // still reported as the receiver sent it
    CHECK_FALSE(in.clock().valid());
}

TEST_CASE("interpreter: BESTVEL is stamped at time tag minus its latency; track in radians")
{
    Interpreter in;
    Velocity v;
    v.header.kind = FrameKind::binary;
    v.header.id = log_id::bestvel;
    v.header.time_status = time_status::finesteering;
    v.header.week = 2080;
    v.header.ms = 412623400;
    v.velocity_type = position_type::psrdiff;
    v.latency_s = 0.15;
    v.horizontal_speed_mps = 3.5;
    v.track_deg = 90.0;
    v.vertical_speed_mps = -0.1;
    const auto out = in.on_message(v, FrameKind::binary, kMeasured + 50'000, 76);
    REQUIRE(out.velocity);
    CHECK(out.velocity->utime == kMeasured - 150'000);
    CHECK_THAT(out.velocity->track_rad, WithinAbs(std::numbers::pi / 2, 1e-12));
    CHECK(out.velocity->horizontal_speed_mps == 3.5);
    CHECK(out.velocity->vertical_speed_mps == -0.1);
    CHECK(out.velocity->velocity_type == 17);
    CHECK_THAT(out.velocity->latency_s, WithinAbs(0.15, 1e-12));
}

TEST_CASE("interpreter: GGA without GST is published at once, stamped with its UTC time")
{
    Interpreter in;
    const double tod = 18 * 3600 + 36 * 60 + 45.4;
    const auto out = in.on_message(gga(tod, 4), FrameKind::nmea, kMeasured + 80'000, 70);
    REQUIRE(out.fix);
    CHECK(out.fix->utime == kDay + 67'005'400'000LL);
    CHECK(out.fix->utime == kMeasured);
    CHECK(out.fix->gps_week == 2080);
    CHECK(out.fix->gps_ms == 412623400);
    CHECK(out.fix->quality == FixQuality::rtk_fixed);
    CHECK(out.fix->position_type == 4);
    CHECK(out.fix->height_m == 65.5);
    CHECK(out.fix->differential_age_s == 3.0);
    CHECK(std::isnan(out.fix->sigma_latitude_m));
    CHECK(out.fix->source == Source::nmea);
}

TEST_CASE("interpreter: once GSTs are seen, a GGA waits for the GST of its epoch and takes its sigmas")
{
    Interpreter in;
    const double t0 = 1000.0;
    const int64_t arrival = kDay + 1'000'100'000LL;
    CHECK_FALSE(in.on_message(gst(t0 - 1.0), FrameKind::nmea, arrival - 1'000'000, 60).fix);
    // GGA of epoch t0: a GST was seen, so it waits.
    CHECK_FALSE(in.on_message(gga(t0, 1), FrameKind::nmea, arrival, 70).fix);
    const auto out = in.on_message(gst(t0), FrameKind::nmea, arrival + 5'000, 60);
    REQUIRE(out.fix);
    CHECK(out.fix->utime == kDay + 1'000'000'000LL);
    CHECK(out.fix->sigma_latitude_m == 0.5);
    CHECK(out.fix->sigma_longitude_m == 0.6);
    CHECK(out.fix->sigma_height_m == 0.9);
    // GST before GGA in the same epoch: published with the GGA.
    CHECK_FALSE(in.on_message(gst(t0 + 1.0), FrameKind::nmea, arrival + 1'000'000, 60).fix);
    const auto out2 = in.on_message(gga(t0 + 1.0, 1), FrameKind::nmea, arrival + 1'005'000, 70);
    REQUIRE(out2.fix);
    CHECK(out2.fix->sigma_latitude_m == 0.5);
    // A GGA whose GST never comes goes out (without sigmas) when the next GGA arrives.
    CHECK_FALSE(in.on_message(gga(t0 + 2.0, 1), FrameKind::nmea, arrival + 2'000'000, 70).fix);
    const auto out3 = in.on_message(gga(t0 + 3.0, 1), FrameKind::nmea, arrival + 3'000'000, 70);
    REQUIRE(out3.fix);
    CHECK(out3.fix->utime == kDay + 1'002'000'000LL);
    CHECK(std::isnan(out3.fix->sigma_latitude_m));
}

TEST_CASE("interpreter: an empty no-fix GGA is a fix of quality NONE stamped on arrival")
{
    InterpreterConfig cfg;
    cfg.output_latency_us = 10'000;
    Interpreter in(cfg);
    Gga g;
    const auto out = in.on_message(g, FrameKind::nmea, 5'000'000'000LL, 26);
    REQUIRE(out.fix);
    CHECK(out.fix->quality == FixQuality::none);
    CHECK(out.fix->utime == 5'000'000'000LL - 10'000);
    CHECK_FALSE(out.fix->time_from_receiver);
    CHECK(std::isnan(out.fix->latitude_deg));
    CHECK(out.fix->gps_week == -1);
}

TEST_CASE("interpreter: BESTPOS wins over GGA from the same receiver; GGA takes over when BESTPOS stops")
{
    Interpreter in;
    const int64_t t = kMeasured;
    REQUIRE(in.on_message(bestpos(time_status::finesteering, 412623400), FrameKind::ascii, t, 200).fix);
    CHECK_FALSE(in.on_message(gga(67005.4, 1), FrameKind::nmea, t + 10'000, 70).fix);
    CHECK(in.superseded() == 1);
    // 2.5 s without BESTPOS: the GGA is used.
    CHECK(in.on_message(gga(67007.9, 1), FrameKind::nmea, t + 2'500'000, 70).fix);
}

TEST_CASE("interpreter: the swri capture (BESTPOSA + GGA + RMC interleaved) gives 40 fixes, all from BESTPOSA")
{
    const auto data = read_capture("swri-novatel_gps_driver/gpgga-gprmc-bestpos.udp-payload.bin");
    Decoder d;
    Interpreter in;
    std::vector<Fix> fixes;
    int velocities = 0;
    // Arrival: the capture's own epoch plus 50 ms (2017-07-12, GPS week 1957).
    d.feed(data.data(), data.size(), 1499898186'800'000LL, [&](const Decoded& m) {
        const auto out = in.on_message(m.message, m.kind, m.arrival_utime, m.frame_bytes);
        if (out.fix) fixes.push_back(*out.fix);
        if (out.velocity) ++velocities;
    });
    REQUIRE(fixes.size() == 40);
    for (const auto& f : fixes) {
        CHECK(f.source == Source::novatel_ascii);
        CHECK(f.quality == FixQuality::single);
        CHECK(f.time_from_receiver);
    }
    // #BESTPOSA week 1957, 339804.750 s -> 2017-07-12T22:23:06.750Z, the first GGA's time.
    CHECK(fixes.front().utime == 1499898186'750'000LL);
    CHECK_THAT(fixes.front().height_m, WithinAbs(255.7484 - 26.0, 1e-9));
    CHECK(velocities == 40);  // from RMC: this receiver logs no BESTVEL
}
