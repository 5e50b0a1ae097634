#include "ugv/novatel/text_fields.hpp"

#include <charconv>
#include <cmath>
#include <limits>

namespace ugv::novatel {

bool FieldReader::next(std::string_view& field)
{
    if (done_) {
        return false;
    }
    if (!rest_.empty() && rest_.front() == '"') {
        const auto close = rest_.find('"', 1);
        if (close != std::string_view::npos) {
            field = rest_.substr(1, close - 1);
            const auto comma = rest_.find(',', close);
            if (comma == std::string_view::npos) {
                done_ = true;
                rest_ = {};
            } else {
                rest_.remove_prefix(comma + 1);
            }
            return true;
        }
    }
    const auto comma = rest_.find(',');
    if (comma == std::string_view::npos) {
        field = rest_;
        rest_ = {};
        done_ = true;
    } else {
        field = rest_.substr(0, comma);
        rest_.remove_prefix(comma + 1);
    }
    return true;
}

bool FieldReader::skip(int n)
{
    std::string_view unused;
    for (int i = 0; i < n; ++i) {
        if (!next(unused)) {
            return false;
        }
    }
    return true;
}

bool parse_double(std::string_view f, double& value)
{
    if (f.empty()) {
        return false;
    }
    if (f.front() == '+') {
        f.remove_prefix(1);
    }
    double v = 0;
    const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
    if (ec != std::errc() || end != f.data() + f.size() || !std::isfinite(v)) {
        return false;
    }
    value = v;
    return true;
}

bool parse_int(std::string_view f, int64_t& value)
{
    if (f.empty()) {
        return false;
    }
    if (f.front() == '+') {
        f.remove_prefix(1);
    }
    int64_t v = 0;
    const auto [end, ec] = std::from_chars(f.data(), f.data() + f.size(), v);
    if (ec != std::errc() || end != f.data() + f.size()) {
        return false;
    }
    value = v;
    return true;
}

bool parse_uint(std::string_view f, uint32_t& value)
{
    int64_t v = 0;
    if (!parse_int(f, v) || v < 0 || v > std::numeric_limits<uint32_t>::max()) {
        return false;
    }
    value = static_cast<uint32_t>(v);
    return true;
}

double parse_nmea_angle(std::string_view value, std::string_view hemisphere)
{
    double raw = 0;
    if (hemisphere.size() != 1 || !parse_double(value, raw) || raw < 0) {
        return std::numeric_limits<double>::quiet_NaN();
    }
    const double degrees = std::floor(raw / 100.0);
    const double minutes = raw - degrees * 100.0;
    if (minutes >= 60.0) {
        return std::numeric_limits<double>::quiet_NaN();
    }
    const double angle = degrees + minutes / 60.0;
    switch (hemisphere.front()) {
    case 'N':
    case 'E': return angle;
    case 'S':
    case 'W': return -angle;
    default: return std::numeric_limits<double>::quiet_NaN();
    }
}

double parse_nmea_time(std::string_view f)
{
    double raw = 0;
    if (f.size() < 6 || !parse_double(f, raw) || raw < 0) {
        return std::numeric_limits<double>::quiet_NaN();
    }
    const double hours = std::floor(raw / 10000.0);
    const double minutes = std::floor((raw - hours * 10000.0) / 100.0);
    const double seconds = raw - hours * 10000.0 - minutes * 100.0;
    if (hours >= 24.0 || minutes >= 60.0 || seconds >= 61.0) {
        return std::numeric_limits<double>::quiet_NaN();
    }
    return hours * 3600.0 + minutes * 60.0 + seconds;
}

}  // namespace ugv::novatel
