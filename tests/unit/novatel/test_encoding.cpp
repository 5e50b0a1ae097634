#include <catch2/catch.hpp>

#include "capture_file.hpp"
#include "ugv/novatel/decoder.hpp"
#include "ugv/novatel/encoding.hpp"

using namespace ugv::novatel;
using ugv::novatel::test::bytes;

TEST_CASE("commands: text as the receiver expects it")
{
    CHECK(unlogall_command() == "UNLOGALL\r\n");
    CHECK(log_command("bestposb", 0.25) == "LOG BESTPOSB ONTIME 0.25\r\n");
    CHECK(log_command("GPGGA", 1.0) == "LOG GPGGA ONTIME 1\r\n");
    CHECK(com_command(115200) == "COM 115200\r\n");
}

TEST_CASE("parse_command: the receiver's reading, with and without a port argument")
{
    auto c = parse_command("log com1 bestposb ontime 0.25");
    CHECK(c.type == Command::Type::log);
    CHECK(c.message == "BESTPOSB");
    CHECK(c.trigger == "ONTIME");
    CHECK(c.period_s == 0.25);
    c = parse_command("LOG BESTVELB ONTIME 1\r\n");
    CHECK(c.message == "BESTVELB");
    CHECK(c.period_s == 1.0);
    c = parse_command("LOG VERSIONA");
    CHECK(c.trigger == "ONCE");
    CHECK(parse_command("unlogall").type == Command::Type::unlogall);
    c = parse_command("COM COM1 57600 N 8 1");
    CHECK(c.type == Command::Type::com);
    CHECK(c.baud == 57600);
    CHECK(parse_command("COM 115200").baud == 115200);
    CHECK(parse_command("FRESET").type == Command::Type::unknown);
    CHECK(parse_command("COM fast").type == Command::Type::unknown);
}

TEST_CASE("encoders round-trip through the decoder: binary, ASCII, NMEA")
{
    Position p;
    p.header.id = log_id::bestpos;
    p.header.time_status = 180;
    p.header.week = 2100;
    p.header.ms = 123456750;
    p.position_type = 50;
    p.latitude_deg = 51.0447;
    p.longitude_deg = -114.0719;
    p.height_msl_m = 1045.25;
    p.undulation_m = -17.0;
    p.sigma_latitude_m = 0.02;
    p.satellites_tracked = 12;
    p.satellites_used = 10;
    const auto bin = encode_binary(p.header, encode_position_body(p));
    std::string stream(bin.begin(), bin.end());
    stream += encode_ascii("BESTPOSA", p.header, position_fields(p));
    Gga g;
    g.talker = "GP";
    g.utc_time_s = 3600.5;
    g.quality = 4;
    g.latitude_deg = 51.0447;
    g.longitude_deg = -114.0719;
    g.altitude_msl_m = 1045.25;
    g.undulation_m = -17.0;
    g.satellites_used = 10;
    stream += encode_nmea(gga_body(g));
    Decoder d;
    std::vector<Position> pos;
    std::vector<Gga> gga;
    const auto data = bytes(stream);
    d.feed(data.data(), data.size(), 0, [&](const Decoded& m) {
        if (const auto* x = std::get_if<Position>(&m.message)) pos.push_back(*x);
        if (const auto* x = std::get_if<Gga>(&m.message)) gga.push_back(*x);
    });
    REQUIRE(pos.size() == 2);
    for (const auto& x : pos) {
        CHECK(x.header.week == 2100);
        CHECK(x.header.ms == 123456750);
        CHECK(x.position_type == 50);
        CHECK_THAT(x.latitude_deg, Catch::Matchers::WithinAbs(51.0447, 1e-10));
        CHECK_THAT(x.height_msl_m, Catch::Matchers::WithinAbs(1045.25, 1e-4));
        CHECK(x.satellites_used == 10);
    }
    REQUIRE(gga.size() == 1);
    CHECK(gga[0].quality == 4);
    CHECK_THAT(gga[0].latitude_deg, Catch::Matchers::WithinAbs(51.0447, 1e-9));
    CHECK_THAT(gga[0].longitude_deg, Catch::Matchers::WithinAbs(-114.0719, 1e-9));
    CHECK_THAT(gga[0].utc_time_s, Catch::Matchers::WithinAbs(3600.5, 1e-9));
    CHECK(d.splitter_counters().crc_errors == 0);
}
