// The one table of the NovAtel logs the driver knows. Binary and ASCII decoding, the
// encoders and the interpreter's source ranking all find a log here, so a log whose body
// has an existing layout is one row. A new layout: its struct (messages.hpp), its file
// in src/layouts/ and its declaration below.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string_view>

namespace ugv::novatel {

// How a body reads and writes in both framings (defined in body_layout.hpp).
struct BodyLayout;
extern const BodyLayout position_layout;  // BESTPOS-like, 72 bytes
extern const BodyLayout velocity_layout;  // BESTVEL-like, 44 bytes
extern const BodyLayout time_layout;      // TIME, 44 bytes

struct LogInfo
{
    uint16_t id;            // binary header message id
    std::string_view name;  // ASCII name without the format letter ("BESTPOS" for BESTPOSA)
    const BodyLayout* layout;
    // Among the sources of the same quantity (position, velocity), lower wins while it keeps
    // arriving (see interpreter.hpp). Unused for a log the interpreter only reads the header of.
    int rank;
};

// Ids from the fact sheet (shared/protocols/novatel-oem4.md).
inline constexpr std::array kLogTable{
    LogInfo{42, "BESTPOS", &position_layout, 0},
    LogInfo{47, "PSRPOS", &position_layout, 1},
    LogInfo{99, "BESTVEL", &velocity_layout, 0},
    LogInfo{100, "PSRVEL", &velocity_layout, 1},
    LogInfo{101, "TIME", &time_layout, 0},
};

// NMEA sentences compete with the logs above for the same quantities; their ranks are
// kept here so that the whole order reads in one place.
namespace nmea_rank {
inline constexpr int gga = 2, rmc = 2, vtg = 3;
}

// Number of ranks (the interpreter keeps one slot per rank).
inline constexpr int kSourceRanks = [] {
    int n = std::max({nmea_rank::gga, nmea_rank::rmc, nmea_rank::vtg});
    for (const auto& log : kLogTable) n = std::max(n, log.rank);
    return n + 1;
}();

// nullptr for a log the table does not hold.
constexpr const LogInfo* find_log(uint16_t id)
{
    for (const auto& log : kLogTable) {
        if (log.id == id) return &log;
    }
    return nullptr;
}

constexpr const LogInfo* find_log(std::string_view name)
{
    for (const auto& log : kLogTable) {
        if (log.name == name) return &log;
    }
    return nullptr;
}

inline std::span<const LogInfo> log_table() { return kLogTable; }

// For code that names a log (the emulator, tests); a new log needs no constant here.
namespace log_id {
// Searches by value, not through find_log's pointer: gcc does not take a pointer's
// comparison with null as a constant expression under -fsanitize=undefined.
consteval uint16_t of(std::string_view name)
{
    for (const auto& log : kLogTable) {
        if (log.name == name) return log.id;
    }
    throw std::logic_error("not in kLogTable");  // a compile error
}
inline constexpr uint16_t bestpos = of("BESTPOS"), psrpos = of("PSRPOS"), bestvel = of("BESTVEL"),
                          psrvel = of("PSRVEL"), time = of("TIME");
}  // namespace log_id

}  // namespace ugv::novatel
