// The BESTVEL body (BESTVEL, PSRVEL, ...): binary offsets and ASCII fields from the fact sheet.
#include <cmath>

#include "body_fields.hpp"
#include "body_layout.hpp"
#include "sanity.hpp"
#include "ugv/novatel/enums.hpp"

namespace ugv::novatel {
namespace {

constexpr double kMaxLatencyS = 60.0;

Message from_binary(const LogHeader& h, const uint8_t* b)
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

bool from_ascii(const LogHeader& h, std::string_view body, Message& out)
{
    Velocity v;
    v.header = h;
    FieldReader r(body);
    std::string_view sol, type;
    if (!r.next(sol) || !r.next(type)) {
        return false;
    }
    v.solution_status = solution_status_from_name(sol);
    v.velocity_type = position_type_from_name(type);
    if (!number(r, v.latency_s) || !number(r, v.age_s) || !number(r, v.horizontal_speed_mps) ||
        !number(r, v.track_deg) || !number(r, v.vertical_speed_mps)) {
        return false;
    }
    out = v;
    return true;
}

bool plausible(const Message& m)
{
    const auto& v = std::get<Velocity>(m);
    // The velocity is valid at the time tag minus the latency, so the latency moves the
    // stamp (in integer us): receivers report tens of ms, never a negative one.
    const bool latency_ok = std::isnan(v.latency_s) || (v.latency_s >= 0.0 && v.latency_s <= kMaxLatencyS);
    return week_ok(v.header) && latency_ok &&
           no_infinity({v.age_s, v.horizontal_speed_mps, v.track_deg, v.vertical_speed_mps});
}

std::vector<uint8_t> to_binary(const Message& m)
{
    const auto* v = std::get_if<Velocity>(&m);
    if (v == nullptr) {
        return {};
    }
    std::vector<uint8_t> b(44, 0);
    put<uint32_t>(b, 0, v->solution_status);
    put<uint32_t>(b, 4, v->velocity_type);
    put<float>(b, 8, static_cast<float>(v->latency_s));
    put<float>(b, 12, static_cast<float>(v->age_s));
    put<double>(b, 16, v->horizontal_speed_mps);
    put<double>(b, 24, v->track_deg);
    put<double>(b, 32, v->vertical_speed_mps);
    return b;
}

std::string to_ascii(const Message& m)
{
    const auto* v = std::get_if<Velocity>(&m);
    if (v == nullptr) {
        return {};
    }
    return enum_name(solution_status_name(v->solution_status), v->solution_status) + "," +
           enum_name(position_type_name(v->velocity_type), v->velocity_type) +
           format(",%.3f,%.3f,%.6f,%.6f,%.6f,0", v->latency_s, v->age_s, v->horizontal_speed_mps, v->track_deg,
                  v->vertical_speed_mps);
}

}  // namespace

const BodyLayout velocity_layout{44, from_binary, from_ascii, plausible, to_binary, to_ascii};

}  // namespace ugv::novatel
