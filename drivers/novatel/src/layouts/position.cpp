// The BESTPOS body (BESTPOS, PSRPOS, ...): binary offsets and ASCII fields from the fact sheet.
#include <algorithm>

#include "body_fields.hpp"
#include "body_layout.hpp"
#include "sanity.hpp"
#include "ugv/novatel/enums.hpp"

namespace ugv::novatel {
namespace {

constexpr uint32_t kWgs84 = 61;

Message from_binary(const LogHeader& h, const uint8_t* b)
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

bool from_ascii(const LogHeader& h, std::string_view body, Message& out)
{
    Position p;
    p.header = h;
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
    p.datum_id = datum == "WGS84" ? kWgs84 : kUnknownEnum;
    p.station_id = std::string(station);
    out = std::move(p);
    return true;
}

bool plausible(const Message& m)
{
    const auto& p = std::get<Position>(m);
    // The binary log carries the satellite counts in one byte each.
    const bool counts_ok = p.satellites_tracked >= -1 && p.satellites_tracked <= 255 && p.satellites_used >= -1 &&
                           p.satellites_used <= 255;
    return week_ok(p.header) && counts_ok && latitude_ok(p.latitude_deg) && longitude_ok(p.longitude_deg) &&
           no_infinity({p.height_msl_m, p.undulation_m, p.sigma_latitude_m, p.sigma_longitude_m, p.sigma_height_m,
                        p.differential_age_s, p.solution_age_s});
}

std::vector<uint8_t> to_binary(const Message& m)
{
    const auto* p = std::get_if<Position>(&m);
    if (p == nullptr) {
        return {};
    }
    std::vector<uint8_t> b(72, 0);
    put<uint32_t>(b, 0, p->solution_status);
    put<uint32_t>(b, 4, p->position_type);
    put<double>(b, 8, p->latitude_deg);
    put<double>(b, 16, p->longitude_deg);
    put<double>(b, 24, p->height_msl_m);
    put<float>(b, 32, static_cast<float>(p->undulation_m));
    put<uint32_t>(b, 36, p->datum_id);
    put<float>(b, 40, static_cast<float>(p->sigma_latitude_m));
    put<float>(b, 44, static_cast<float>(p->sigma_longitude_m));
    put<float>(b, 48, static_cast<float>(p->sigma_height_m));
    std::memcpy(b.data() + 52, p->station_id.data(), std::min<std::size_t>(4, p->station_id.size()));
    put<float>(b, 56, static_cast<float>(p->differential_age_s));
    put<float>(b, 60, static_cast<float>(p->solution_age_s));
    b[64] = static_cast<uint8_t>(std::max(0, p->satellites_tracked));
    b[65] = static_cast<uint8_t>(std::max(0, p->satellites_used));
    return b;
}

std::string to_ascii(const Message& m)
{
    const auto* p = std::get_if<Position>(&m);
    if (p == nullptr) {
        return {};
    }
    return enum_name(solution_status_name(p->solution_status), p->solution_status) + "," +
           enum_name(position_type_name(p->position_type), p->position_type) +
           format(",%.11f,%.11f,%.4f,%.4f,WGS84,%.4f,%.4f,%.4f,\"%s\",%.3f,%.3f,%d,%d,0,0,0,06,00,03",
                  p->latitude_deg, p->longitude_deg, p->height_msl_m, p->undulation_m, p->sigma_latitude_m,
                  p->sigma_longitude_m, p->sigma_height_m, p->station_id.c_str(), p->differential_age_s,
                  p->solution_age_s, p->satellites_tracked, p->satellites_used);
}

}  // namespace

const BodyLayout position_layout{72, from_binary, from_ascii, plausible, to_binary, to_ascii};

}  // namespace ugv::novatel
