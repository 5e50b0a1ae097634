// NMEA 0183 sentences GGA, RMC, VTG, GST. Empty fields (a receiver without a fix sends
// "$GPGGA,,,,,,0,,,,,,,,*66") decode to NaN values and quality 0: a valid "no fix".
#include <array>

#include "ugv/novatel/log_decoding.hpp"
#include "ugv/novatel/text_fields.hpp"

namespace ugv::novatel {
namespace {

constexpr double kKnotToMps = 1852.0 / 3600.0;
constexpr double kKmhToMps = 1.0 / 3.6;

// Up to 16 fields of a sentence; the ones it does not have stay empty.
using Fields = std::array<std::string_view, 16>;

std::size_t read_fields(FieldReader& r, Fields& f)
{
    std::size_t n = 0;
    while (n < f.size() && r.next(f[n])) {
        ++n;
    }
    return n;
}

int to_int(std::string_view field, int def)
{
    int64_t v = 0;
    return parse_int(field, v) ? static_cast<int>(v) : def;
}

double to_double(std::string_view field)
{
    double v = kNaN;
    parse_double(field, v);
    return v;
}

DecodeStatus gga(FieldReader& r, std::string talker, Message& out)
{
    Fields f;
    // Differential age and station id (fields 13, 14) are often omitted entirely.
    if (read_fields(r, f) < 12) {
        return DecodeStatus::malformed;
    }
    Gga g;
    g.talker = std::move(talker);
    g.utc_time_s = parse_nmea_time(f[0]);
    g.latitude_deg = parse_nmea_angle(f[1], f[2]);
    g.longitude_deg = parse_nmea_angle(f[3], f[4]);
    g.quality = to_int(f[5], 0);
    g.satellites_used = to_int(f[6], -1);
    g.hdop = to_double(f[7]);
    g.altitude_msl_m = to_double(f[8]);
    g.undulation_m = to_double(f[10]);
    g.differential_age_s = to_double(f[12]);
    g.station_id = std::string(f[13]);
    out = std::move(g);
    return DecodeStatus::decoded;
}

DecodeStatus rmc(FieldReader& r, std::string talker, Message& out)
{
    Fields f;
    if (read_fields(r, f) < 9) {
        return DecodeStatus::malformed;
    }
    Rmc m;
    m.talker = std::move(talker);
    m.utc_time_s = parse_nmea_time(f[0]);
    m.valid = f[1] == "A";
    m.latitude_deg = parse_nmea_angle(f[2], f[3]);
    m.longitude_deg = parse_nmea_angle(f[4], f[5]);
    m.speed_mps = to_double(f[6]) * kKnotToMps;
    m.track_deg = to_double(f[7]);
    int64_t date = 0;
    if (f[8].size() == 6 && parse_int(f[8], date)) {
        m.day = static_cast<int>(date / 10000);
        m.month = static_cast<int>(date / 100 % 100);
        m.year = 2000 + static_cast<int>(date % 100);  // two-digit year: this century
    }
    out = std::move(m);
    return DecodeStatus::decoded;
}

DecodeStatus vtg(FieldReader& r, std::string talker, Message& out)
{
    Fields f;
    if (read_fields(r, f) < 8) {
        return DecodeStatus::malformed;
    }
    Vtg v;
    v.talker = std::move(talker);
    v.track_deg = to_double(f[0]);
    v.speed_mps = to_double(f[6]) * kKmhToMps;
    if (v.speed_mps != v.speed_mps) {  // km/h empty: fall back on knots
        v.speed_mps = to_double(f[4]) * kKnotToMps;
    }
    out = std::move(v);
    return DecodeStatus::decoded;
}

DecodeStatus gst(FieldReader& r, std::string talker, Message& out)
{
    Fields f;
    if (read_fields(r, f) < 8) {
        return DecodeStatus::malformed;
    }
    Gst g;
    g.talker = std::move(talker);
    g.utc_time_s = parse_nmea_time(f[0]);
    g.rms_m = to_double(f[1]);
    g.semi_major_m = to_double(f[2]);
    g.semi_minor_m = to_double(f[3]);
    g.orientation_deg = to_double(f[4]);
    g.sigma_latitude_m = to_double(f[5]);
    g.sigma_longitude_m = to_double(f[6]);
    g.sigma_altitude_m = to_double(f[7]);
    out = std::move(g);
    return DecodeStatus::decoded;
}

}  // namespace

DecodeStatus decode_nmea(const uint8_t* frame, std::size_t size, Message& out, std::string_view& address)
{
    if (size < 4) {
        return DecodeStatus::malformed;
    }
    // Between the '$' and the "*hh" checksum.
    const std::string_view text(reinterpret_cast<const char*>(frame) + 1, size - 4);
    FieldReader r(text);
    r.next(address);
    // Standard sentences are a 2-letter talker then a 3-letter type; proprietary ones start
    // with 'P' and are not ours.
    if (address.size() != 5 || address.front() == 'P') {
        return DecodeStatus::unknown;
    }
    std::string talker(address.substr(0, 2));
    const std::string_view type = address.substr(2);
    if (type == "GGA") return gga(r, std::move(talker), out);
    if (type == "RMC") return rmc(r, std::move(talker), out);
    if (type == "VTG") return vtg(r, std::move(talker), out);
    if (type == "GST") return gst(r, std::move(talker), out);
    return DecodeStatus::unknown;
}

}  // namespace ugv::novatel
