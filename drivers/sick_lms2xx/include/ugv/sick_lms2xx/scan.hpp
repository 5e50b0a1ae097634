// The 0xB0 scan telegram:
//   B0 | COUNT (u16 LE) | N x VALUE (u16 LE) | [real-time scan index] | STATUS
// COUNT bits 0-9: N; bits 11-12: partial-scan index (0.25 deg steps); bit 13: not
// interpreted (passed through); bits 14-15: units (0 = cm, 1 = mm).
// VALUE (8/80 m measuring mode): bits 0-12 range, bits 13/14/15 field A/B/C flags. The top
// range codes are not ranges: they become NaN with a BeamFlag.
#pragma once

#include <cstdint>
#include <vector>

#include "ugv/sick_lms2xx/telegram.hpp"

namespace ugv::sick_lms2xx {

enum class Units : uint8_t { cm = 0, mm = 1 };

// Per-beam flag codes; the values equal laser_scan_t's FLAG_* constants.
enum class BeamFlag : int8_t { ok = 0, invalid = 1, dazzle = 2, overflow = 3, low_signal = 4, error = 5, other = 6 };

// Special range codes (13-bit range field).
namespace code {
inline constexpr uint16_t invalid = 8191;
inline constexpr uint16_t dazzle = 8190;
inline constexpr uint16_t overflow = 8189;
inline constexpr uint16_t low_signal = 8187;
inline constexpr uint16_t channel1_error = 8186;
inline constexpr uint16_t above_maximum = 8183;
inline constexpr uint16_t first_special = 8183;  // every code from here up is not a range
}  // namespace code

inline constexpr uint16_t kRangeMask = 0x1fff;
inline constexpr uint16_t kCountMask = 0x03ff;
inline constexpr std::size_t kMaxValues = 401;  // 100 deg at 0.25 deg

inline double unit_m(Units u) { return u == Units::mm ? 0.001 : 0.01; }
// The largest range a value can express in these units (the code just below the special ones).
inline double range_max_m(Units u) { return (code::first_special - 1) * unit_m(u); }
BeamFlag classify_range_code(uint16_t range_code);

struct Scan
{
    Units units = Units::mm;
    int partial_index = 0;          // 0-3, in 0.25 deg steps
    bool count_bit13 = false;       // meaning unverified; kept for diagnostics
    std::vector<float> ranges_m;    // NaN where flags[i] != ok
    std::vector<int8_t> flags;      // BeamFlag values
    std::vector<uint8_t> fields;    // bit 0 field A, bit 1 field B, bit 2 field C
    int32_t scan_index = -1;        // the real-time scan index, -1 when not sent
    uint8_t status = 0;
};

enum class ScanError { none, not_a_scan, bad_units, length_mismatch };
const char* to_string(ScanError e);

// Decodes t into out (its vectors are reused, so a steady stream does not allocate). Whether
// a scan index follows the values is read from LEN: 0 extra bytes = none, 1 = u8, 2 = u16 LE.
ScanError decode_scan(const Telegram& t, Scan& out);

// The VALUE word a device sends for range_m in units plus field bits; for emulators. A range
// beyond the largest expressible one, or +infinity (no echo), is sent as code::above_maximum;
// NaN or a negative range as code::invalid.
uint16_t encode_range(double range_m, Units units, uint8_t field_bits = 0);
// A whole 0xB0 scan telegram (for emulators and tests). scan_index < 0: none sent;
// otherwise sent as one byte (modulo 256).
std::vector<uint8_t> encode_scan_telegram(const std::vector<uint16_t>& values, Units units, int partial_index,
                                          int scan_index, uint8_t status);

}  // namespace ugv::sick_lms2xx
