// Decoded values of real frames (README cross-checks) and the edge cases of each framing.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "capture_file.hpp"
#include "ugv/novatel/decoder.hpp"
#include "ugv/novatel/encoding.hpp"
#include "ugv/novatel/enums.hpp"

using namespace ugv::novatel;
using Catch::Matchers::WithinAbs;
using ugv::novatel::test::bytes;
using ugv::novatel::test::read_capture;

namespace {

template <typename T>
std::vector<T> decode_all(const std::vector<uint8_t>& data)
{
    Decoder d;
    std::vector<T> out;
    d.feed(data.data(), data.size(), 0, [&](const Decoded& m) {
        if (const auto* v = std::get_if<T>(&m.message)) {
            out.push_back(*v);
        }
    });
    return out;
}

}  // namespace

TEST_CASE("binary BESTPOS/BESTVEL: the README's first values of the swri capture")
{
    const auto data = read_capture("swri-novatel_gps_driver/bestpos-bestvel-psrdop2-sync.tcp-payload.bin");
    const auto pos = decode_all<Position>(data);
    REQUIRE(pos.size() == 33);
    const Position& p = pos.front();
    CHECK(p.header.kind == FrameKind::binary);
    CHECK(p.header.id == log_id::bestpos);
    CHECK(p.header.week == 2080);
    CHECK(p.header.ms == 412623400);
    CHECK(p.header.time_status == time_status::finesteering);
    CHECK(p.solution_status == solution_status::sol_computed);
    CHECK(p.position_type == position_type::single);
    CHECK(p.latitude_deg == 29.443919376635606);
    CHECK(p.longitude_deg == -98.61475813065091);
    CHECK_THAT(p.height_msl_m, WithinAbs(259.5874, 1e-4));
    CHECK(p.undulation_m == -26.0);
    CHECK(p.datum_id == 61);

    const auto vel = decode_all<Velocity>(data);
    REQUIRE(vel.size() == 33);
    CHECK_THAT(vel.front().horizontal_speed_mps, WithinAbs(0.004193, 1e-6));
    CHECK_THAT(vel.front().track_deg, WithinAbs(56.3045, 1e-4));
    CHECK_THAT(vel.front().vertical_speed_mps, WithinAbs(0.024802, 1e-6));
}

TEST_CASE("binary BESTPOS: an unknown position type (74 = INS_PPP on SPAN) decodes, reported as unknown")
{
    const auto data = read_capture("swri-novatel_gps_driver/corrimudata.tcp-payload.bin");
    const auto pos = decode_all<Position>(data);
    REQUIRE(pos.size() == 28);
    CHECK(pos.front().position_type == 74);
    CHECK_FALSE(position_type_name(74).has_value());
    CHECK(pos.front().header.week == 1820);
}

TEST_CASE("binary and ASCII twins (GAVLab ParsingData) decode to the same BESTPOS values")
{
    const auto bestpos_only = [](std::vector<Position> all) {
        std::erase_if(all, [](const Position& p) { return p.header.id != log_id::bestpos; });
        return all;
    };
    const auto bin = bestpos_only(decode_all<Position>(read_capture("gavlab-novatel/ParsingData.GPS")));
    const auto asc = bestpos_only(decode_all<Position>(read_capture("gavlab-novatel/ParsingData.ASC")));
    REQUIRE(bin.size() == 84);
    REQUIRE(asc.size() == 84);
    CHECK(bin.front().header.ms == 419234000);
    CHECK(bin.front().latitude_deg == 32.5953599864694);
    CHECK(bin.front().longitude_deg == -85.29567377157181);
    CHECK_THAT(bin.front().height_msl_m, WithinAbs(200.914, 1e-3));
    for (std::size_t i = 0; i < bin.size(); ++i) {
        INFO(i);
        CHECK(asc[i].header.kind == FrameKind::ascii);
        CHECK(asc[i].header.week == bin[i].header.week);
        CHECK(asc[i].header.ms == bin[i].header.ms);
        CHECK(asc[i].header.time_status == bin[i].header.time_status);
        CHECK(asc[i].solution_status == bin[i].solution_status);
        CHECK(asc[i].position_type == bin[i].position_type);
        CHECK_THAT(asc[i].latitude_deg, WithinAbs(bin[i].latitude_deg, 1e-10));
        CHECK_THAT(asc[i].longitude_deg, WithinAbs(bin[i].longitude_deg, 1e-10));
        CHECK_THAT(asc[i].height_msl_m, WithinAbs(bin[i].height_msl_m, 1e-4));
        CHECK_THAT(asc[i].sigma_latitude_m, WithinAbs(bin[i].sigma_latitude_m, 1e-4));
        CHECK(asc[i].satellites_tracked == bin[i].satellites_tracked);
        CHECK(asc[i].satellites_used == bin[i].satellites_used);
    }
    const auto bvel = decode_all<Velocity>(read_capture("gavlab-novatel/ParsingData.GPS"));
    REQUIRE(bvel.size() == 1);
    CHECK_THAT(bvel.front().horizontal_speed_mps, WithinAbs(0.006833, 1e-6));
    CHECK_THAT(bvel.front().track_deg, WithinAbs(124.6005, 1e-4));
}

TEST_CASE("ASCII: TIMEA from the swri capture; an unknown enum name is kUnknownEnum, not an error")
{
    const auto times = decode_all<TimeLog>(read_capture("swri-novatel_gps_driver/gpgga-gprmc-bestpos.udp-payload.bin"));
    REQUIRE(times.size() == 2);
    CHECK(times.front().header.week == 1957);
    CHECK(times.front().utc_status == 1);
    CHECK_THAT(times.front().utc_offset_s, WithinAbs(-18.0, 1e-9));

    Position p;
    p.header.time_status = time_status::finesteering;
    p.header.week = 1957;
    p.header.ms = 339804750;
    std::string fields = position_fields(p);
    fields.replace(fields.find("NONE"), 4, "SOMETHING_NEW");
    const std::string line = encode_ascii("BESTPOSA", p.header, fields);
    const auto pos = decode_all<Position>(bytes(line));
    REQUIRE(pos.size() == 1);
    CHECK(pos.front().position_type == kUnknownEnum);
    CHECK(pos.front().header.ms == 339804750);
}

TEST_CASE("NMEA: GGA/RMC from the NovAtel receiver of the swri capture")
{
    const auto data = read_capture("swri-novatel_gps_driver/gpgga-gprmc-bestpos.udp-payload.bin");
    const auto gga = decode_all<Gga>(data);
    REQUIRE(gga.size() == 40);
    // $GPGGA,222306.75,2926.6326,N,09836.8840,W,1,08,1.2,255.75,M,-26.00,M,,*57
    CHECK(gga[0].talker == "GP");
    CHECK_THAT(gga[0].utc_time_s, WithinAbs(22 * 3600 + 23 * 60 + 6.75, 1e-9));
    CHECK_THAT(gga[0].latitude_deg, WithinAbs(29 + 26.6326 / 60, 1e-12));
    CHECK_THAT(gga[0].longitude_deg, WithinAbs(-(98 + 36.8840 / 60), 1e-12));
    CHECK(gga[0].quality == 1);
    CHECK(gga[0].satellites_used == 8);
    CHECK(gga[0].hdop == 1.2);
    CHECK(gga[0].altitude_msl_m == 255.75);
    CHECK(gga[0].undulation_m == -26.0);
    CHECK(std::isnan(gga[0].differential_age_s));
    const auto rmc = decode_all<Rmc>(data);
    REQUIRE(rmc.size() == 40);
    // $GPRMC,222306.75,A,2926.6326482,N,09836.8840339,W,0.044,80.0,120717,0.0,E,A*11
    CHECK(rmc[0].valid);
    CHECK_THAT(rmc[0].speed_mps, WithinAbs(0.044 * 1852.0 / 3600.0, 1e-12));
    CHECK(rmc[0].track_deg == 80.0);
    CHECK(rmc[0].year == 2017);
    CHECK(rmc[0].month == 7);
    CHECK(rmc[0].day == 12);
}

TEST_CASE("NMEA: empty no-fix sentences are a valid 'no fix', not errors")
{
    Decoder d;
    std::vector<Gga> gga;
    std::vector<Vtg> vtg;
    const auto data = bytes("$GPGGA,,,,,,0,,,,,,,,*66\r\n$GPGGA,001901.00,,,,,0,00,99.99,,,,,,*6F\r\n$GPVTG,,,,,,,,,N*30\r\n");
    d.feed(data.data(), data.size(), 0, [&](const Decoded& m) {
        if (const auto* g = std::get_if<Gga>(&m.message)) gga.push_back(*g);
        if (const auto* v = std::get_if<Vtg>(&m.message)) vtg.push_back(*v);
    });
    REQUIRE(gga.size() == 2);
    CHECK(gga[0].quality == 0);
    CHECK(std::isnan(gga[0].latitude_deg));
    CHECK(std::isnan(gga[0].utc_time_s));
    CHECK(gga[1].quality == 0);
    CHECK_THAT(gga[1].utc_time_s, WithinAbs(19 * 60 + 1.0, 1e-9));
    REQUIRE(vtg.size() == 1);
    CHECK(std::isnan(vtg[0].speed_mps));
    CHECK(d.counters().malformed == 0);
    CHECK(d.splitter_counters().crc_errors == 0);
}

TEST_CASE("NMEA: GST sigmas (gpsd polarx2 log) and VTG speed")
{
    const auto data = read_capture("gpsd-test-daemon/polarx2.log");
    const auto gst = decode_all<Gst>(data);
    REQUIRE(gst.size() == 5);
    // $GPGST,112257.00,0.387,317.719,3.872,1.791,317.563,10.659,180.746*61
    CHECK_THAT(gst[0].utc_time_s, WithinAbs(11 * 3600 + 22 * 60 + 57.0, 1e-9));
    CHECK(gst[0].rms_m == 0.387);
    CHECK(gst[0].sigma_latitude_m == 317.563);
    CHECK(gst[0].sigma_longitude_m == 10.659);
    CHECK(gst[0].sigma_altitude_m == 180.746);
    const auto vtg = decode_all<Vtg>(data);
    REQUIRE(vtg.size() == 5);
    CHECK(std::isfinite(vtg[0].speed_mps));
}

TEST_CASE("decoder: unknown ids and sentences are counted by id/name; a short body is malformed")
{
    LogHeader h;
    h.id = 43;  // RANGE
    auto range = encode_binary(h, std::vector<uint8_t>(48, 0));
    h.id = log_id::bestpos;
    auto short_bestpos = encode_binary(h, std::vector<uint8_t>(40, 0));
    std::vector<uint8_t> data = range;
    data.insert(data.end(), short_bestpos.begin(), short_bestpos.end());
    const auto gsv = encode_nmea("GPGSV,1,1,00");
    data.insert(data.end(), gsv.begin(), gsv.end());
    Decoder d;
    int decoded = 0;
    d.feed(data.data(), data.size(), 0, [&](const Decoded&) { ++decoded; });
    CHECK(decoded == 0);
    CHECK(d.counters().unknown_binary_ids.at(43) == 1);
    CHECK(d.counters().unknown_names.at("GPGSV") == 1);
    CHECK(d.counters().unknown_total == 2);
    CHECK(d.counters().malformed == 1);
}

TEST_CASE("decoder: each frame of a batch gets its own arrival time (bytes after it / baud)")
{
    // Two 104-byte frames read in one 208-byte chunk at 9600 baud: the first one's last
    // byte arrived 104 bytes * 10 bits / 9600 = 108.333 ms before the chunk's stamp.
    Position p;
    p.header.id = log_id::bestpos;
    auto f1 = encode_binary(p.header, encode_position_body(p));
    const auto f2 = f1;
    f1.insert(f1.end(), f2.begin(), f2.end());
    Decoder d;
    d.set_baud(9600);
    std::vector<int64_t> arrivals;
    d.feed(f1.data(), f1.size(), 10'000'000, [&](const Decoded& m) { arrivals.push_back(m.arrival_utime); });
    REQUIRE(arrivals.size() == 2);
    CHECK(arrivals[0] == 10'000'000 - 108'333);
    CHECK(arrivals[1] == 10'000'000);
}

TEST_CASE("replies and prompts come out as Reply")
{
    const auto data = bytes("<OK\r\n[COM1]<ERROR:Invalid Message ID\r\n");
    const auto replies = decode_all<Reply>(data);
    REQUIRE(replies.size() == 3);
    CHECK(replies[0].text == "OK");
    CHECK(replies[0].kind == FrameKind::reply);
    CHECK(replies[1].text == "[COM1]");
    CHECK(replies[1].kind == FrameKind::prompt);
    CHECK(replies[2].text == "ERROR:Invalid Message ID");
}

// Found by fuzz_gps_stream / fuzz_gps_frame: frames with a valid checksum but impossible
// content (NMEA's 8-bit checksum passes 1 corrupted sentence in 256; a binary double can hold
// anything) came out as fixes at latitude 401 deg or 3e35 deg, with -1077536624 satellites,
// or overflowed the time stamp (signed overflow, UB) with a latency of 1e30 s or week 4e9.
TEST_CASE("decoder: a checksummed frame with impossible values is malformed, not a fix")
{
    Position p;
    p.latitude_deg = 29.44;
    p.longitude_deg = -98.61;
    p.height_msl_m = 259.6;
    LogHeader h;
    h.id = log_id::bestpos;
    Position off_globe = p;
    off_globe.latitude_deg = 401.57;
    Position infinite_height = p;
    infinite_height.height_msl_m = INFINITY;
    Position many_satellites = p;
    many_satellites.satellites_tracked = 100000;
    Velocity infinite_speed;
    infinite_speed.horizontal_speed_mps = -INFINITY;
    Velocity negative_latency;
    negative_latency.latency_s = -0.5;
    Velocity huge_latency;
    huge_latency.latency_s = 1e30;
    LogHeader huge_week = h;
    huge_week.week = 4'000'000'000u;
    LogHeader hv;
    hv.id = log_id::bestvel;

    std::vector<uint8_t> data;
    const auto append = [&](const std::vector<uint8_t>& frame) { data.insert(data.end(), frame.begin(), frame.end()); };
    const auto append_text = [&](const std::string& frame) { data.insert(data.end(), frame.begin(), frame.end()); };
    append(encode_binary(h, encode_position_body(off_globe)));
    append(encode_binary(h, encode_position_body(infinite_height)));
    append_text(encode_ascii("BESTPOSA", h, position_fields(many_satellites)));  // binary has 1 byte for it
    append(encode_binary(hv, encode_velocity_body(infinite_speed)));
    append(encode_binary(hv, encode_velocity_body(negative_latency)));
    append(encode_binary(hv, encode_velocity_body(huge_latency)));
    append_text(encode_ascii("BESTPOSA", huge_week, position_fields(p)));
    // 40134.5749 = 401 deg 34.57 min; longitude 19000.0 = 190 deg.
    append_text(encode_nmea("GPGGA,120000.00,40134.5749,N,09345.0343,W,1,10,0.9,246.7,M,-31.4,M,,"));
    append_text(encode_nmea("GPRMC,120000.00,A,4013.4575,N,19000.0000,E,0.0,0.0,010120,,,A"));
    append(encode_binary(h, encode_position_body(p)));  // the one good frame

    Decoder d;
    std::vector<Position> positions;
    int others = 0;
    d.feed(data.data(), data.size(), 0, [&](const Decoded& m) {
        if (const auto* v = std::get_if<Position>(&m.message)) positions.push_back(*v);
        else ++others;
    });
    CHECK(d.counters().malformed == 9);
    CHECK(others == 0);
    REQUIRE(positions.size() == 1);
    CHECK_THAT(positions[0].latitude_deg, WithinAbs(29.44, 1e-9));
}
