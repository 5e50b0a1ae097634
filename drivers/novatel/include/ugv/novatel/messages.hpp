// The decoded logs and sentences: plain values, units in the names, NaN for a field the
// frame left empty. Raw receiver enums are kept as numbers (see enums.hpp).
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <variant>

#include "ugv/novatel/log_table.hpp"  // log_id, for the users of these structs
#include "ugv/novatel/stream_splitter.hpp"

namespace ugv::novatel {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// The header shared by binary and ASCII logs. Short headers (binary AA 44 13, ASCII %)
// carry only the id/name, week and milliseconds; the other fields stay at their defaults.
struct LogHeader
{
    FrameKind kind = FrameKind::binary;
    uint16_t id = 0;
    bool response = false;            // binary message-type bit 7: a reply to a command
    uint16_t sequence = 0;
    double idle_percent = kNaN;
    uint32_t time_status = 20;        // time_status::unknown unless the log says otherwise
    uint32_t week = 0;
    uint32_t ms = 0;                  // milliseconds into the GPS week
    uint32_t receiver_status = 0;
    uint16_t software_build = 0;
};

// The BESTPOS body layout (the logs that have it: log_table.hpp).
struct Position
{
    LogHeader header;
    uint32_t solution_status = 0;
    uint32_t position_type = 0;
    double latitude_deg = kNaN;
    double longitude_deg = kNaN;
    double height_msl_m = kNaN;       // above mean sea level
    double undulation_m = kNaN;       // geoid above ellipsoid: ellipsoidal h = MSL + undulation
    uint32_t datum_id = 0;
    double sigma_latitude_m = kNaN;
    double sigma_longitude_m = kNaN;
    double sigma_height_m = kNaN;
    std::string station_id;
    double differential_age_s = kNaN;
    double solution_age_s = kNaN;
    int satellites_tracked = -1;      // #obs
    int satellites_used = -1;         // #GPS L1 used in the solution
};

// The BESTVEL body layout.
struct Velocity
{
    LogHeader header;
    uint32_t solution_status = 0;
    uint32_t velocity_type = 0;
    double latency_s = kNaN;          // the velocity is valid at the time tag minus this
    double age_s = kNaN;
    double horizontal_speed_mps = kNaN;
    double track_deg = kNaN;          // over ground, clockwise from true north
    double vertical_speed_mps = kNaN; // up positive
};

// TIME: the receiver clock model and the GPS-UTC offset it knows.
struct TimeLog
{
    LogHeader header;
    uint32_t clock_status = 0;        // 0 VALID, 1 CONVERGING, 2 ITERATING, 3 INVALID
    double receiver_clock_offset_s = kNaN;
    double receiver_clock_offset_std_s = kNaN;
    double utc_offset_s = kNaN;       // UTC = GPS time + this (about -18 s)
    uint32_t utc_year = 0;
    uint32_t utc_month = 0, utc_day = 0, utc_hour = 0, utc_minute = 0;
    uint32_t utc_ms = 0;              // ms of the minute
    uint32_t utc_status = 0;          // 0 INVALID, 1 VALID, 2 WARNING
};

// NMEA sentences. utc_time_s: seconds of the UTC day, NaN when the field is empty.
struct Gga
{
    std::string talker;               // "GP", "GN", ...
    double utc_time_s = kNaN;
    double latitude_deg = kNaN;
    double longitude_deg = kNaN;
    int quality = 0;                  // 0 invalid, 1 single, 2 differential, 4 RTK fixed, 5 RTK float,
                                      // 6 dead reckoning, 7 fixed position, 8 simulator, 9 WAAS
    int satellites_used = -1;
    double hdop = kNaN;
    double altitude_msl_m = kNaN;
    double undulation_m = kNaN;
    double differential_age_s = kNaN;
    std::string station_id;
};

struct Rmc
{
    std::string talker;
    double utc_time_s = kNaN;
    bool valid = false;               // status 'A'
    double latitude_deg = kNaN;
    double longitude_deg = kNaN;
    double speed_mps = kNaN;
    double track_deg = kNaN;
    int year = 0, month = 0, day = 0; // 0 when the date field is empty
};

struct Vtg
{
    std::string talker;
    double track_deg = kNaN;
    double speed_mps = kNaN;
};

struct Gst
{
    std::string talker;
    double utc_time_s = kNaN;
    double rms_m = kNaN;
    double semi_major_m = kNaN;
    double semi_minor_m = kNaN;
    double orientation_deg = kNaN;
    double sigma_latitude_m = kNaN;
    double sigma_longitude_m = kNaN;
    double sigma_altitude_m = kNaN;
};

// A command reply (<OK, <ERROR:...) or a port prompt ([COM1]).
struct Reply
{
    FrameKind kind = FrameKind::reply;
    std::string text;                 // without the leading '<' for replies, e.g. "OK"
};

using Message = std::variant<Position, Velocity, TimeLog, Gga, Rmc, Vtg, Gst, Reply>;

}  // namespace ugv::novatel
