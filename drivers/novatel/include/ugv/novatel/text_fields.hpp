// Comma-separated fields of ASCII logs and NMEA sentences, and number parsing that treats
// an empty field as "not given" (NaN) rather than an error.
#pragma once

#include <cstdint>
#include <string_view>

namespace ugv::novatel {

// Walks the fields of one record. A field starting with '"' runs to the closing quote (a
// quoted string is one field even if it holds commas); the quotes are stripped.
class FieldReader
{
public:
    explicit FieldReader(std::string_view text) : rest_(text), done_(false) {}
    // False when there is no next field.
    bool next(std::string_view& field);
    // Skips n fields; false if there were fewer.
    bool skip(int n);

private:
    std::string_view rest_;
    bool done_;
};

// Strict parses: the whole field must be the number. Empty -> false (callers keep NaN/defaults).
bool parse_double(std::string_view field, double& value);
bool parse_int(std::string_view field, int64_t& value);
bool parse_uint(std::string_view field, uint32_t& value);

// NMEA angle "ddmm.mmmm" (or "dddmm.mmmm") with hemisphere 'N','S','E','W' -> signed degrees.
// NaN when either field is empty or malformed.
double parse_nmea_angle(std::string_view value, std::string_view hemisphere);
// NMEA time "hhmmss.ss" -> seconds of the day; NaN when empty or malformed.
double parse_nmea_time(std::string_view field);

}  // namespace ugv::novatel
