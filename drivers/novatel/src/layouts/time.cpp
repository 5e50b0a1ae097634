// The TIME body: the receiver clock model and the UTC offset (fact sheet: OEM4 TIME log).
#include <array>

#include "body_fields.hpp"
#include "body_layout.hpp"
#include "sanity.hpp"
#include "ugv/novatel/enums.hpp"

namespace ugv::novatel {
namespace {

// Index = the enum value.
constexpr std::array<std::string_view, 4> kClockStatus{"VALID", "CONVERGING", "ITERATING", "INVALID"};
constexpr std::array<std::string_view, 3> kUtcStatus{"INVALID", "VALID", "WARNING"};

template <std::size_t N>
uint32_t from_name(const std::array<std::string_view, N>& names, std::string_view name)
{
    for (std::size_t i = 0; i < N; ++i) {
        if (names[i] == name) return static_cast<uint32_t>(i);
    }
    return kUnknownEnum;
}

template <std::size_t N>
std::string to_name(const std::array<std::string_view, N>& names, uint32_t value)
{
    return enum_name(value < N ? std::optional(names[value]) : std::nullopt, value);
}

Message from_binary(const LogHeader& h, const uint8_t* b)
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

bool from_ascii(const LogHeader& h, std::string_view body, Message& out)
{
    TimeLog t;
    t.header = h;
    FieldReader r(body);
    std::string_view clock, year, month, day, hour, minute, ms, utc;
    if (!r.next(clock) || !number(r, t.receiver_clock_offset_s) || !number(r, t.receiver_clock_offset_std_s) ||
        !number(r, t.utc_offset_s) || !r.next(year) || !r.next(month) || !r.next(day) || !r.next(hour) ||
        !r.next(minute) || !r.next(ms) || !r.next(utc)) {
        return false;
    }
    t.clock_status = from_name(kClockStatus, clock);
    t.utc_status = from_name(kUtcStatus, utc);
    if (!parse_uint(year, t.utc_year) || !parse_uint(month, t.utc_month) || !parse_uint(day, t.utc_day) ||
        !parse_uint(hour, t.utc_hour) || !parse_uint(minute, t.utc_minute) || !parse_uint(ms, t.utc_ms)) {
        return false;
    }
    out = t;
    return true;
}

bool plausible(const Message& m) { return week_ok(std::get<TimeLog>(m).header); }

std::vector<uint8_t> to_binary(const Message& m)
{
    const auto* t = std::get_if<TimeLog>(&m);
    if (t == nullptr) {
        return {};
    }
    std::vector<uint8_t> b(44, 0);
    put<uint32_t>(b, 0, t->clock_status);
    put<double>(b, 4, t->receiver_clock_offset_s);
    put<double>(b, 12, t->receiver_clock_offset_std_s);
    put<double>(b, 20, t->utc_offset_s);
    put<uint32_t>(b, 28, t->utc_year);
    b[32] = static_cast<uint8_t>(t->utc_month);
    b[33] = static_cast<uint8_t>(t->utc_day);
    b[34] = static_cast<uint8_t>(t->utc_hour);
    b[35] = static_cast<uint8_t>(t->utc_minute);
    put<uint32_t>(b, 36, t->utc_ms);
    put<uint32_t>(b, 40, t->utc_status);
    return b;
}

std::string to_ascii(const Message& m)
{
    const auto* t = std::get_if<TimeLog>(&m);
    if (t == nullptr) {
        return {};
    }
    return to_name(kClockStatus, t->clock_status) +
           format(",%.9e,%.9e,%.11f,%u,%u,%u,%u,%u,%u,", t->receiver_clock_offset_s, t->receiver_clock_offset_std_s,
                  t->utc_offset_s, t->utc_year, t->utc_month, t->utc_day, t->utc_hour, t->utc_minute, t->utc_ms) +
           to_name(kUtcStatus, t->utc_status);
}

}  // namespace

const BodyLayout time_layout{44, from_binary, from_ascii, plausible, to_binary, to_ascii};

}  // namespace ugv::novatel
