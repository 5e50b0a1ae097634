// NovAtel OEM4 enumerations: value <-> name. A value outside the tables is "unknown" (and
// stays available as its raw number), never an error: receivers newer than these tables send
// values we do not know (a real one sent position type 74).
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

namespace ugv::novatel {

// Raw value used when an ASCII log carries an enum name that is not in our tables.
inline constexpr uint32_t kUnknownEnum = 0xFFFFFFFFU;

namespace time_status {
inline constexpr uint32_t unknown = 20, approximate = 60, coarseadjusting = 80, coarse = 100,
                          coarsesteering = 120, freewheeling = 130, fineadjusting = 140, fine = 160,
                          finebackupsteering = 170, finesteering = 180, sattime = 200;
}  // namespace time_status

namespace position_type {
inline constexpr uint32_t none = 0, fixedpos = 1, fixedheight = 2, floatconv = 4, widelane = 5, narrowlane = 6,
                          doppler_velocity = 8, single = 16, psrdiff = 17, waas = 18, propagated = 19,
                          omnistar = 20, l1_float = 32, ionofree_float = 33, narrow_float = 34, l1_int = 48,
                          wide_int = 49, narrow_int = 50, ins_first = 51, ins_last = 56,
                          omnistar_hp = 64, omnistar_xp = 65, cdgps = 66, ppp_converging = 68, ppp = 69;
}  // namespace position_type

namespace solution_status {
inline constexpr uint32_t sol_computed = 0, insufficient_obs = 1;
}

// Names as the receiver prints them in ASCII logs; nullopt for a value not in the table.
std::optional<std::string_view> solution_status_name(uint32_t value);
std::optional<std::string_view> position_type_name(uint32_t value);
std::optional<std::string_view> time_status_name(uint32_t value);

// Name -> value; kUnknownEnum for a name not in the table.
uint32_t solution_status_from_name(std::string_view name);
uint32_t position_type_from_name(std::string_view name);
uint32_t time_status_from_name(std::string_view name);

}  // namespace ugv::novatel
