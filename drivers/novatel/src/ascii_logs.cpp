// NovAtel ASCII logs: "#NAMEA,port,seq,idle,timestatus,week,seconds,rxstatus,reserved,sw;body"
// and short "%NAMEA,week,seconds;body". Enums are printed as names.
#include <cmath>

#include "ugv/novatel/enums.hpp"
#include "ugv/novatel/checksum.hpp"
#include "ugv/novatel/log_decoding.hpp"
#include "ugv/novatel/text_fields.hpp"

namespace ugv::novatel {
namespace {

uint16_t id_of(std::string_view base)
{
    if (base == "BESTPOS") return log_id::bestpos;
    if (base == "PSRPOS") return log_id::psrpos;
    if (base == "BESTVEL") return log_id::bestvel;
    if (base == "PSRVEL") return log_id::psrvel;
    if (base == "TIME") return log_id::time;
    return 0;
}

bool parse_seconds_ms(std::string_view field, uint32_t& ms)
{
    double seconds = 0;
    if (!parse_double(field, seconds) || seconds < 0 || seconds > 604800.0) {
        return false;
    }
    ms = static_cast<uint32_t>(std::llround(seconds * 1000.0));
    return true;
}

bool parse_hex_field(std::string_view field, uint32_t& value)
{
    return !field.empty() && field.size() <= 8 &&
           parse_hex(reinterpret_cast<const uint8_t*>(field.data()), field.size(), value);
}

bool parse_header(std::string_view text, FrameKind kind, LogHeader& h)
{
    FieldReader r(text);
    std::string_view f;
    h.kind = kind;
    r.next(f);  // the name, already read by the caller
    if (kind == FrameKind::ascii_short) {
        uint32_t week = 0;
        if (!r.next(f) || !parse_uint(f, week) || !r.next(f) || !parse_seconds_ms(f, h.ms)) {
            return false;
        }
        h.week = week;
        return true;
    }
    std::string_view port, seq, idle, status, week, seconds, rx, reserved, sw;
    if (!r.next(port) || !r.next(seq) || !r.next(idle) || !r.next(status) || !r.next(week) ||
        !r.next(seconds) || !r.next(rx) || !r.next(reserved) || !r.next(sw)) {
        return false;
    }
    uint32_t sequence = 0, build = 0;
    if (!parse_uint(seq, sequence) || !parse_uint(week, h.week) || !parse_seconds_ms(seconds, h.ms) ||
        !parse_hex_field(rx, h.receiver_status)) {
        return false;
    }
    h.sequence = static_cast<uint16_t>(sequence);
    parse_double(idle, h.idle_percent);
    if (parse_uint(sw, build)) {
        h.software_build = static_cast<uint16_t>(build);
    }
    h.time_status = time_status_from_name(status);
    return true;
}

// Fills d from a field when it holds a number; an empty field leaves the NaN default.
bool number(FieldReader& r, double& d)
{
    std::string_view f;
    if (!r.next(f)) {
        return false;
    }
    parse_double(f, d);
    return true;
}

bool count(FieldReader& r, int& n)
{
    std::string_view f;
    if (!r.next(f)) {
        return false;
    }
    int64_t v = 0;
    if (parse_int(f, v)) {
        n = static_cast<int>(v);
    }
    return true;
}

bool position_body(std::string_view body, Position& p)
{
    FieldReader r(body);
    std::string_view sol, type, datum, station;
    if (!r.next(sol) || !r.next(type)) {
        return false;
    }
    p.solution_status = solution_status_from_name(sol);
    p.position_type = position_type_from_name(type);
    if (!number(r, p.latitude_deg) || !number(r, p.longitude_deg) || !number(r, p.height_msl_m) ||
        !number(r, p.undulation_m) || !r.next(datum) || !number(r, p.sigma_latitude_m) ||
        !number(r, p.sigma_longitude_m) || !number(r, p.sigma_height_m) || !r.next(station) ||
        !number(r, p.differential_age_s) || !number(r, p.solution_age_s) || !count(r, p.satellites_tracked) ||
        !count(r, p.satellites_used)) {
        return false;
    }
    p.datum_id = datum == "WGS84" ? 61U : kUnknownEnum;
    p.station_id = std::string(station);
    return true;
}

bool velocity_body(std::string_view body, Velocity& v)
{
    FieldReader r(body);
    std::string_view sol, type;
    if (!r.next(sol) || !r.next(type)) {
        return false;
    }
    v.solution_status = solution_status_from_name(sol);
    v.velocity_type = position_type_from_name(type);
    return number(r, v.latency_s) && number(r, v.age_s) && number(r, v.horizontal_speed_mps) &&
           number(r, v.track_deg) && number(r, v.vertical_speed_mps);
}

uint32_t clock_status_from_name(std::string_view n)
{
    if (n == "VALID") return 0;
    if (n == "CONVERGING") return 1;
    if (n == "ITERATING") return 2;
    if (n == "INVALID") return 3;
    return kUnknownEnum;
}

uint32_t utc_status_from_name(std::string_view n)
{
    if (n == "INVALID") return 0;
    if (n == "VALID") return 1;
    if (n == "WARNING") return 2;
    return kUnknownEnum;
}

bool time_body(std::string_view body, TimeLog& t)
{
    FieldReader r(body);
    std::string_view clock, year, month, day, hour, minute, ms, utc;
    if (!r.next(clock) || !number(r, t.receiver_clock_offset_s) || !number(r, t.receiver_clock_offset_std_s) ||
        !number(r, t.utc_offset_s) || !r.next(year) || !r.next(month) || !r.next(day) || !r.next(hour) ||
        !r.next(minute) || !r.next(ms) || !r.next(utc)) {
        return false;
    }
    t.clock_status = clock_status_from_name(clock);
    t.utc_status = utc_status_from_name(utc);
    return parse_uint(year, t.utc_year) && parse_uint(month, t.utc_month) && parse_uint(day, t.utc_day) &&
           parse_uint(hour, t.utc_hour) && parse_uint(minute, t.utc_minute) && parse_uint(ms, t.utc_ms);
}

}  // namespace

DecodeStatus decode_ascii(const uint8_t* frame, std::size_t size, FrameKind kind, Message& out,
                          std::string_view& name)
{
    // Between the '#'/'%' and the "*xxxxxxxx" checksum.
    if (size < 10) {
        return DecodeStatus::malformed;
    }
    const std::string_view text(reinterpret_cast<const char*>(frame) + 1, size - 10);
    const auto semicolon = text.find(';');
    name = text.substr(0, text.find(','));
    if (semicolon == std::string_view::npos || name.empty() || name.size() > semicolon) {
        return DecodeStatus::malformed;
    }
    // The last letter is the format (A = ASCII); the id is the name without it.
    const uint16_t id = id_of(name.substr(0, name.size() - 1));
    if (name.back() != 'A' || id == 0) {
        return DecodeStatus::unknown;
    }
    LogHeader h;
    if (!parse_header(text.substr(0, semicolon), kind, h)) {
        return DecodeStatus::malformed;
    }
    h.id = id;
    const std::string_view body = text.substr(semicolon + 1);
    switch (id) {
    case log_id::bestpos:
    case log_id::psrpos: {
        Position p;
        p.header = h;
        if (!position_body(body, p)) {
            return DecodeStatus::malformed;
        }
        out = std::move(p);
        return DecodeStatus::decoded;
    }
    case log_id::bestvel:
    case log_id::psrvel: {
        Velocity v;
        v.header = h;
        if (!velocity_body(body, v)) {
            return DecodeStatus::malformed;
        }
        out = v;
        return DecodeStatus::decoded;
    }
    default: {
        TimeLog t;
        t.header = h;
        if (!time_body(body, t)) {
            return DecodeStatus::malformed;
        }
        out = t;
        return DecodeStatus::decoded;
    }
    }
}

}  // namespace ugv::novatel
