// The 0xB0 scan telegram: count word, units, values, field flags, special codes, scan index.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "ugv/sick_lms2xx/crc.hpp"
#include "ugv/sick_lms2xx/decoder.hpp"
#include "ugv/sick_lms2xx/scan.hpp"

using namespace ugv::sick_lms2xx;
using Bytes = std::vector<uint8_t>;

namespace {

// Decodes exactly one telegram from bytes.
ScanError decode_one(const Bytes& frame, Scan& scan)
{
    Decoder dec;
    ScanError err = ScanError::not_a_scan;
    int n = 0;
    dec.feed(frame.data(), frame.size(), [&](const DecoderEvent& ev) {
        if (ev.kind != DecoderEvent::Kind::telegram) return;
        ++n;
        err = decode_scan(ev.telegram, scan);
    });
    REQUIRE(n == 1);
    return err;
}

Bytes with_crc(Bytes b)
{
    const uint16_t crc = crc16(b.data(), b.size());
    put_u16le(b, crc);
    return b;
}

}  // namespace

TEST_CASE("a hand-built scan telegram in mm", "[sick_lms2xx][scan]")
{
    // COUNT 0x4003: 3 values, units mm. Values: 1000 mm; 500 mm with field A; dazzle.
    const Bytes frame = with_crc({0x02, 0x80, 0x0A, 0x00, 0xB0, 0x03, 0x40, 0xE8, 0x03, 0xF4, 0x21, 0xFE, 0x1F, 0x10});
    Scan s;
    REQUIRE(decode_one(frame, s) == ScanError::none);
    CHECK(s.units == Units::mm);
    CHECK(s.partial_index == 0);
    CHECK(s.scan_index == -1);
    CHECK(s.status == 0x10);
    REQUIRE(s.ranges_m.size() == 3);
    CHECK(s.ranges_m[0] == Approx(1.000f));
    CHECK(s.flags[0] == static_cast<int8_t>(BeamFlag::ok));
    CHECK(s.fields[0] == 0);
    CHECK(s.ranges_m[1] == Approx(0.500f));
    CHECK(s.fields[1] == 0x1);
    CHECK(std::isnan(s.ranges_m[2]));
    CHECK(s.flags[2] == static_cast<int8_t>(BeamFlag::dazzle));
}

TEST_CASE("cm units, partial-scan index and a one-byte scan index", "[sick_lms2xx][scan]")
{
    // COUNT: 2 values, partial index 3 (bits 11-12), units cm (bits 14-15 = 0): 0x1802.
    // Values 8182 (81.82 m, the largest range) and 123 cm with fields B and C; index 0x7F.
    const Bytes frame = with_crc({0x02, 0x80, 0x09, 0x00, 0xB0, 0x02, 0x18, 0xF6, 0x1F, 0x7B, 0xC0, 0x7F, 0x00});
    Scan s;
    REQUIRE(decode_one(frame, s) == ScanError::none);
    CHECK(s.units == Units::cm);
    CHECK(s.partial_index == 3);
    CHECK_FALSE(s.count_bit13);
    CHECK(s.ranges_m[0] == Approx(81.82f));
    CHECK(s.ranges_m[1] == Approx(1.23f));
    CHECK(s.fields[1] == 0x6);
    CHECK(s.scan_index == 0x7F);
}

TEST_CASE("a two-byte scan index", "[sick_lms2xx][scan]")
{
    const Bytes frame = with_crc({0x02, 0x80, 0x08, 0x00, 0xB0, 0x01, 0x40, 0x64, 0x00, 0x34, 0x12, 0x00});
    Scan s;
    REQUIRE(decode_one(frame, s) == ScanError::none);
    CHECK(s.ranges_m[0] == Approx(0.1f));
    CHECK(s.scan_index == 0x1234);
}

TEST_CASE("every special range code becomes NaN with its flag", "[sick_lms2xx][scan]")
{
    const std::vector<std::pair<uint16_t, BeamFlag>> cases = {
        {8191, BeamFlag::invalid},   {8190, BeamFlag::dazzle}, {8189, BeamFlag::overflow},
        {8187, BeamFlag::low_signal}, {8186, BeamFlag::error},  {8183, BeamFlag::overflow},
        {8188, BeamFlag::other},     {8185, BeamFlag::other},  {8184, BeamFlag::other},
    };
    std::vector<uint16_t> values;
    for (const auto& [c, f] : cases) values.push_back(static_cast<uint16_t>(c | 0xE000));  // all field bits set
    values.push_back(8182);
    Scan s;
    REQUIRE(decode_one(encode_scan_telegram(values, Units::mm, 0, -1, 0), s) == ScanError::none);
    REQUIRE(s.ranges_m.size() == cases.size() + 1);
    for (std::size_t i = 0; i < cases.size(); ++i) {
        INFO("code " << cases[i].first);
        CHECK(std::isnan(s.ranges_m[i]));
        CHECK(s.flags[i] == static_cast<int8_t>(cases[i].second));
        CHECK(s.fields[i] == 0x7);
    }
    CHECK(s.ranges_m.back() == Approx(8.182f));
    CHECK(s.flags.back() == static_cast<int8_t>(BeamFlag::ok));
    CHECK(range_max_m(Units::mm) == Approx(8.182));
    CHECK(range_max_m(Units::cm) == Approx(81.82));
}

TEST_CASE("BeamFlag values equal laser_scan_t FLAG_* constants", "[sick_lms2xx][scan]")
{
    // laser_scan_t: OK 0, INVALID 1, DAZZLE 2, OVERFLOW 3, LOW_SIGNAL 4, ERROR 5, OTHER 6.
    CHECK(static_cast<int>(BeamFlag::ok) == 0);
    CHECK(static_cast<int>(BeamFlag::invalid) == 1);
    CHECK(static_cast<int>(BeamFlag::dazzle) == 2);
    CHECK(static_cast<int>(BeamFlag::overflow) == 3);
    CHECK(static_cast<int>(BeamFlag::low_signal) == 4);
    CHECK(static_cast<int>(BeamFlag::error) == 5);
    CHECK(static_cast<int>(BeamFlag::other) == 6);
}

TEST_CASE("malformed scans are rejected", "[sick_lms2xx][scan]")
{
    Scan s;
    // Units bits 3.
    CHECK(decode_one(with_crc({0x02, 0x80, 0x06, 0x00, 0xB0, 0x01, 0xC0, 0x64, 0x00, 0x00}), s) == ScanError::bad_units);
    // COUNT says 3 values, only 1 present.
    CHECK(decode_one(with_crc({0x02, 0x80, 0x06, 0x00, 0xB0, 0x03, 0x40, 0x64, 0x00, 0x00}), s) ==
          ScanError::length_mismatch);
    // Three extra bytes after the values.
    CHECK(decode_one(with_crc({0x02, 0x80, 0x09, 0x00, 0xB0, 0x01, 0x40, 0x64, 0x00, 1, 2, 3, 0x00}), s) ==
          ScanError::length_mismatch);
    // Not a scan.
    CHECK(decode_one(with_crc({0x02, 0x80, 0x03, 0x00, 0xA0, 0x00, 0x10}), s) == ScanError::not_a_scan);
}

TEST_CASE("encode_range rounds, clamps and marks invalid", "[sick_lms2xx][scan]")
{
    CHECK(encode_range(1.2344, Units::mm) == 1234);
    CHECK(encode_range(1.2346, Units::mm) == 1235);
    CHECK(encode_range(12.34, Units::cm) == 1234);
    CHECK(encode_range(9.0, Units::mm) == code::above_maximum);
    CHECK(encode_range(NAN, Units::mm) == code::invalid);
    CHECK(encode_range(INFINITY, Units::mm) == code::above_maximum);
    CHECK(encode_range(-1.0, Units::mm) == code::invalid);
    CHECK(encode_range(1.0, Units::mm, 0x1) == (1000 | 0x2000));
}

TEST_CASE("a 361-value scan is 732 bytes and round-trips", "[sick_lms2xx][scan]")
{
    std::vector<uint16_t> values(361);
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = static_cast<uint16_t>(i * 20);
    const Bytes frame = encode_scan_telegram(values, Units::mm, 0, 5, 0x10);
    CHECK(frame.size() == 733);  // 732 + the scan index byte
    const Bytes plain = encode_scan_telegram(values, Units::mm, 0, -1, 0x10);
    CHECK(plain.size() == 732);
    Scan s;
    REQUIRE(decode_one(frame, s) == ScanError::none);
    REQUIRE(s.ranges_m.size() == 361);
    CHECK(s.scan_index == 5);
    for (std::size_t i = 0; i < values.size(); ++i) CHECK(s.ranges_m[i] == Approx(values[i] * 0.001f));
}
