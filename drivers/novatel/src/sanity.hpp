// Range checks behind "a valid checksum does not make the content sane", shared by the
// body layouts and the NMEA checks in the decoder.
#pragma once

#include <cmath>
#include <initializer_list>

#include "ugv/novatel/messages.hpp"

namespace ugv::novatel {

inline bool no_infinity(std::initializer_list<double> values)
{
    for (const double v : values) {
        if (std::isinf(v)) return false;
    }
    return true;
}

// NaN (the field was empty) or a coordinate on the globe.
inline bool latitude_ok(double deg) { return std::isnan(deg) || (deg >= -90.0 && deg <= 90.0); }
inline bool longitude_ok(double deg) { return std::isnan(deg) || (deg >= -180.0 && deg <= 180.0); }

// An ASCII header's week is text: the binary header carries it in 16 bits (and a larger
// one overflows the time stamp).
inline bool week_ok(const LogHeader& h) { return h.week <= 0xFFFF; }

}  // namespace ugv::novatel
