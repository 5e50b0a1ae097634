// The log table is the one place a log is declared: each log is listed once, and every
// row decodes in both framings with no other code naming it.
#include <catch2/catch.hpp>

#include <optional>
#include <set>
#include <string>
#include <vector>

#include "capture_file.hpp"
#include "ugv/novatel/decoder.hpp"
#include "ugv/novatel/encoding.hpp"
#include "ugv/novatel/enums.hpp"
#include "ugv/novatel/log_table.hpp"

using namespace ugv::novatel;
using ugv::novatel::test::bytes;

namespace {

// The header of a NovAtel log message; nullptr for NMEA sentences and replies.
LogHeader* header_of(Message& m)
{
    return std::visit(
        [](auto& x) -> LogHeader* {
            if constexpr (requires { x.header; }) return &x.header;
            return nullptr;
        },
        m);
}

// One message per body layout. Float fields hold values a 32-bit float keeps exactly, so
// the binary and ASCII decodings print alike. A new layout needs one here.
std::vector<Message> samples()
{
    Position p;
    p.solution_status = solution_status::sol_computed;
    p.position_type = position_type::narrow_int;
    p.latitude_deg = 51.0447;
    p.longitude_deg = -114.0719;
    p.height_msl_m = 1045.25;
    p.undulation_m = -17.0;
    p.datum_id = 61;
    p.sigma_latitude_m = 0.015625;
    p.sigma_longitude_m = 0.03125;
    p.sigma_height_m = 0.0625;
    p.station_id = "131";
    p.differential_age_s = 1.5;
    p.solution_age_s = 0.0;
    p.satellites_tracked = 12;
    p.satellites_used = 10;
    Velocity v;
    v.velocity_type = position_type::psrdiff;
    v.latency_s = 0.25;
    v.age_s = 0.5;
    v.horizontal_speed_mps = 2.5;
    v.track_deg = 271.25;
    v.vertical_speed_mps = -0.125;
    TimeLog t;
    t.clock_status = 0;
    t.receiver_clock_offset_s = 8.362273445e-09;
    t.receiver_clock_offset_std_s = 5.355026719e-11;
    t.utc_offset_s = -18.0;
    t.utc_year = 2017;
    t.utc_month = 7;
    t.utc_day = 12;
    t.utc_hour = 22;
    t.utc_minute = 23;
    t.utc_ms = 7000;
    t.utc_status = 1;
    return {p, v, t};
}

// The sample whose struct the log's layout encodes.
std::optional<Message> sample_for(const LogInfo& log)
{
    for (const auto& m : samples()) {
        if (!encode_body(log, m).empty()) return m;
    }
    return std::nullopt;
}

std::vector<Message> decode(const std::vector<uint8_t>& data, DecoderCounters& counters)
{
    Decoder d;
    std::vector<Message> out;
    d.feed(data.data(), data.size(), 0, [&](const Decoded& m) { out.push_back(m.message); });
    counters = d.counters();
    return out;
}

}  // namespace

TEST_CASE("log table: each log once, found by its id and by its name")
{
    std::set<uint16_t> ids;
    std::set<std::string_view> names;
    for (const auto& log : log_table()) {
        INFO(log.name);
        CHECK(ids.insert(log.id).second);
        CHECK(names.insert(log.name).second);
        CHECK(find_log(log.id) == &log);
        CHECK(find_log(log.name) == &log);
        CHECK(log.layout != nullptr);
        CHECK((log.rank >= 0 && log.rank < kSourceRanks));
        // The name is the base name: the framing letter (A, B) is not part of it.
        CHECK(find_log(std::string(log.name) + "A") == nullptr);
    }
    CHECK(find_log(uint16_t{43}) == nullptr);  // RANGE: a log we do not decode
    CHECK(find_log("RANGE") == nullptr);
    CHECK(find_log(log_id::bestpos)->name == "BESTPOS");
    CHECK(find_log(log_id::psrvel)->name == "PSRVEL");
}

TEST_CASE("log table: the source ranks of the fact sheet (BESTPOS > PSRPOS > GGA, BESTVEL > PSRVEL > RMC > VTG)")
{
    CHECK(find_log("BESTPOS")->rank < find_log("PSRPOS")->rank);
    CHECK(find_log("PSRPOS")->rank < nmea_rank::gga);
    CHECK(find_log("BESTVEL")->rank < find_log("PSRVEL")->rank);
    CHECK(find_log("PSRVEL")->rank < nmea_rank::rmc);
    CHECK(nmea_rank::rmc < nmea_rank::vtg);
}

TEST_CASE("log table: every log decodes in both framings from its encoded body")
{
    for (const auto& log : log_table()) {
        INFO(log.name);
        auto sample = sample_for(log);
        REQUIRE(sample);  // a new layout: add its sample above
        LogHeader& h = *header_of(*sample);
        h.id = log.id;
        h.time_status = time_status::finesteering;
        h.week = 1957;
        h.ms = 339806000;
        const std::vector<uint8_t> body = encode_body(log, *sample);
        const std::string fields = encode_fields(log, *sample);
        REQUIRE_FALSE(fields.empty());

        DecoderCounters counters;
        auto binary = decode(encode_binary(h, body), counters);
        CHECK(counters.malformed + counters.unknown_total == 0);
        auto ascii = decode(bytes(encode_ascii(std::string(log.name) + "A", h, fields)), counters);
        CHECK(counters.malformed + counters.unknown_total == 0);
        REQUIRE(binary.size() == 1);
        REQUIRE(ascii.size() == 1);
        for (auto* m : {&binary.front(), &ascii.front()}) {
            CHECK(m->index() == sample->index());
            REQUIRE(header_of(*m) != nullptr);
            CHECK(header_of(*m)->id == log.id);
            CHECK(header_of(*m)->week == 1957);
            CHECK(header_of(*m)->ms == 339806000);
            CHECK(header_of(*m)->time_status == time_status::finesteering);
        }
        CHECK(header_of(binary.front())->kind == FrameKind::binary);
        CHECK(header_of(ascii.front())->kind == FrameKind::ascii);
        // Re-encoding what was decoded gives the same body: every field was read.
        CHECK(encode_body(log, binary.front()) == body);
        CHECK(encode_fields(log, ascii.front()) == fields);
        // Both framings carry the same values.
        CHECK(encode_fields(log, binary.front()) == fields);
    }
}
