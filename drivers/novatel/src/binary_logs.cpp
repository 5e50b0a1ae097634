// OEM4 binary logs: little-endian header and bodies (offsets from the fact sheet).
#include <cstring>

#include "ugv/novatel/log_decoding.hpp"

namespace ugv::novatel {
namespace {

constexpr std::size_t kShortHeader = 12;
constexpr std::size_t kCrcBytes = 4;
constexpr std::size_t kPositionBody = 72;  // BESTPOS / PSRPOS
constexpr std::size_t kVelocityBody = 44;  // BESTVEL / PSRVEL
constexpr std::size_t kTimeBody = 44;

template <typename T>
T get(const uint8_t* p)
{
    T v;
    std::memcpy(&v, p, sizeof v);  // the host is little-endian like the receiver (x86, ARM)
    return v;
}

LogHeader long_header(const uint8_t* f)
{
    LogHeader h;
    h.kind = FrameKind::binary;
    h.id = get<uint16_t>(f + 4);
    h.response = (f[6] & 0x80U) != 0;
    h.sequence = get<uint16_t>(f + 10);
    h.idle_percent = f[12] / 2.0;
    h.time_status = f[13];
    h.week = get<uint16_t>(f + 14);
    h.ms = get<uint32_t>(f + 16);
    h.receiver_status = get<uint32_t>(f + 20);
    h.software_build = get<uint16_t>(f + 26);
    return h;
}

LogHeader short_header(const uint8_t* f)
{
    LogHeader h;
    h.kind = FrameKind::binary_short;
    h.id = get<uint16_t>(f + 4);
    h.week = get<uint16_t>(f + 6);
    h.ms = get<uint32_t>(f + 8);
    return h;
}

Position position(const LogHeader& h, const uint8_t* b)
{
    Position p;
    p.header = h;
    p.solution_status = get<uint32_t>(b + 0);
    p.position_type = get<uint32_t>(b + 4);
    p.latitude_deg = get<double>(b + 8);
    p.longitude_deg = get<double>(b + 16);
    p.height_msl_m = get<double>(b + 24);
    p.undulation_m = get<float>(b + 32);
    p.datum_id = get<uint32_t>(b + 36);
    p.sigma_latitude_m = get<float>(b + 40);
    p.sigma_longitude_m = get<float>(b + 44);
    p.sigma_height_m = get<float>(b + 48);
    const char* station = reinterpret_cast<const char*>(b + 52);
    p.station_id.assign(station, strnlen(station, 4));
    p.differential_age_s = get<float>(b + 56);
    p.solution_age_s = get<float>(b + 60);
    p.satellites_tracked = b[64];
    p.satellites_used = b[65];
    return p;
}

Velocity velocity(const LogHeader& h, const uint8_t* b)
{
    Velocity v;
    v.header = h;
    v.solution_status = get<uint32_t>(b + 0);
    v.velocity_type = get<uint32_t>(b + 4);
    v.latency_s = get<float>(b + 8);
    v.age_s = get<float>(b + 12);
    v.horizontal_speed_mps = get<double>(b + 16);
    v.track_deg = get<double>(b + 24);
    v.vertical_speed_mps = get<double>(b + 32);
    return v;
}

TimeLog time_log(const LogHeader& h, const uint8_t* b)
{
    TimeLog t;
    t.header = h;
    t.clock_status = get<uint32_t>(b + 0);
    t.receiver_clock_offset_s = get<double>(b + 4);
    t.receiver_clock_offset_std_s = get<double>(b + 12);
    t.utc_offset_s = get<double>(b + 20);
    t.utc_year = get<uint32_t>(b + 28);
    t.utc_month = b[32];
    t.utc_day = b[33];
    t.utc_hour = b[34];
    t.utc_minute = b[35];
    t.utc_ms = get<uint32_t>(b + 36);
    t.utc_status = get<uint32_t>(b + 40);
    return t;
}

}  // namespace

DecodeStatus decode_binary(const uint8_t* f, std::size_t size, FrameKind kind, Message& out, uint16_t& id)
{
    const bool is_short = kind == FrameKind::binary_short;
    const std::size_t header_len = is_short ? kShortHeader : f[3];
    if (size < header_len + kCrcBytes) {
        return DecodeStatus::malformed;
    }
    const LogHeader h = is_short ? short_header(f) : long_header(f);
    id = h.id;
    if (h.response) {
        return DecodeStatus::response;
    }
    const uint8_t* body = f + header_len;
    const std::size_t body_len = size - header_len - kCrcBytes;
    switch (h.id) {
    case log_id::bestpos:
    case log_id::psrpos:
        if (body_len < kPositionBody) {
            return DecodeStatus::malformed;
        }
        out = position(h, body);
        return DecodeStatus::decoded;
    case log_id::bestvel:
    case log_id::psrvel:
        if (body_len < kVelocityBody) {
            return DecodeStatus::malformed;
        }
        out = velocity(h, body);
        return DecodeStatus::decoded;
    case log_id::time:
        if (body_len < kTimeBody) {
            return DecodeStatus::malformed;
        }
        out = time_log(h, body);
        return DecodeStatus::decoded;
    default: return DecodeStatus::unknown;
    }
}

}  // namespace ugv::novatel
