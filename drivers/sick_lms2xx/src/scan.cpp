#include "ugv/sick_lms2xx/scan.hpp"

#include <cmath>
#include <limits>

namespace ugv::sick_lms2xx {

BeamFlag classify_range_code(uint16_t range_code)
{
    switch (range_code) {
    case code::invalid: return BeamFlag::invalid;
    case code::dazzle: return BeamFlag::dazzle;
    case code::overflow: return BeamFlag::overflow;
    case code::above_maximum: return BeamFlag::overflow;
    case code::low_signal: return BeamFlag::low_signal;
    case code::channel1_error: return BeamFlag::error;
    default: return range_code >= code::first_special ? BeamFlag::other : BeamFlag::ok;
    }
}

const char* to_string(ScanError e)
{
    switch (e) {
    case ScanError::none: return "ok";
    case ScanError::not_a_scan: return "not a 0xB0 scan telegram";
    case ScanError::bad_units: return "scan units bits are neither cm nor mm";
    case ScanError::length_mismatch: return "scan value count does not match the telegram length";
    }
    return "?";
}

ScanError decode_scan(const Telegram& t, Scan& out)
{
    if (t.command != cmd::scan || t.data.size() < 2) return ScanError::not_a_scan;
    const uint8_t* d = t.data.data();
    const uint16_t count_word = get_u16le(d);
    const std::size_t n = count_word & kCountMask;
    const unsigned unit_bits = count_word >> 14;
    if (unit_bits > 1) return ScanError::bad_units;
    if (t.data.size() < 2 + 2 * n) return ScanError::length_mismatch;
    const std::size_t extra = t.data.size() - 2 - 2 * n;
    if (extra > 2) return ScanError::length_mismatch;

    out.units = static_cast<Units>(unit_bits);
    out.partial_index = static_cast<int>((count_word >> 11) & 0x3);
    out.count_bit13 = (count_word & 0x2000) != 0;
    out.status = t.status;
    out.ranges_m.resize(n);
    out.flags.resize(n);
    out.fields.resize(n);
    const float unit = static_cast<float>(unit_m(out.units));
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const uint8_t* v = d + 2;
    for (std::size_t i = 0; i < n; ++i, v += 2) {
        const uint16_t w = get_u16le(v);
        const uint16_t range = w & kRangeMask;
        out.fields[i] = static_cast<uint8_t>(w >> 13);
        if (range < code::first_special) {
            out.ranges_m[i] = static_cast<float>(range) * unit;
            out.flags[i] = static_cast<int8_t>(BeamFlag::ok);
        } else {
            out.ranges_m[i] = nan;
            out.flags[i] = static_cast<int8_t>(classify_range_code(range));
        }
    }
    if (extra == 0) out.scan_index = -1;
    else if (extra == 1) out.scan_index = v[0];
    else out.scan_index = get_u16le(v);
    return ScanError::none;
}

uint16_t encode_range(double range_m, Units units, uint8_t field_bits)
{
    uint16_t range = code::invalid;
    if (std::isinf(range_m) && range_m > 0.0) {
        range = code::above_maximum;  // no echo: nothing within the measuring range
    } else if (std::isfinite(range_m) && range_m >= 0.0) {
        const double counts = std::round(range_m / unit_m(units));
        range = counts >= code::first_special ? code::above_maximum : static_cast<uint16_t>(counts);
    }
    return static_cast<uint16_t>(range | ((field_bits & 0x7) << 13));
}

std::vector<uint8_t> encode_scan_telegram(const std::vector<uint16_t>& values, Units units, int partial_index,
                                          int scan_index, uint8_t status)
{
    std::vector<uint8_t> data;
    data.reserve(2 + 2 * values.size() + 1);
    const auto count_word = static_cast<uint16_t>((values.size() & kCountMask) | ((partial_index & 0x3) << 11) |
                                                  (static_cast<unsigned>(units) << 14));
    put_u16le(data, count_word);
    for (const uint16_t v : values) put_u16le(data, v);
    if (scan_index >= 0) data.push_back(static_cast<uint8_t>(scan_index & 0xff));
    return encode_reply(cmd::scan, data, status);
}

}  // namespace ugv::sick_lms2xx
