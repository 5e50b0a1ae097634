#include <catch2/catch.hpp>

#include "capture_file.hpp"
#include "ugv/novatel/checksum.hpp"

using namespace ugv::novatel;
using ugv::novatel::test::bytes;
using ugv::novatel::test::from_hex;

TEST_CASE("crc32: known answers of the NovAtel variant (init 0, no final xor)")
{
    // zlib.crc32(d, 0xFFFFFFFF) ^ 0xFFFFFFFF
    const auto check = bytes("123456789");
    CHECK(crc32(check.data(), check.size()) == 0x2DFD2D88U);
    const auto a = bytes("a");
    CHECK(crc32(a.data(), a.size()) == 0x3AB551CEU);
    CHECK(crc32(nullptr, 0) == 0U);
}

TEST_CASE("crc32: a real PSRDOP2B frame (swri capture) checks, and the CRC over frame+CRC is 0")
{
    const auto frame = from_hex(
        "aa44121c8b0402a01c000000b4b42008282298180000000002081a1b77beff3f1d5ae43faaf1723fae47c13f0100000000000000dd24"
        "663f21b7a30b");
    REQUIRE(frame.size() == 28 + 28 + 4);
    CHECK(crc32(frame.data(), frame.size() - 4) == 0x0BA3B721U);
    CHECK(crc32(frame.data(), frame.size()) == 0U);
}

TEST_CASE("crc32: continuing a computation equals one pass, at every split")
{
    const auto text = bytes("BESTPOSA,COM1,0,65.5,FINESTEERING,1687,419928.000,00000000,6145,3153;SOL_COMPUTED");
    const uint32_t whole = crc32(text.data(), text.size());
    for (std::size_t k = 0; k <= text.size(); ++k) {
        CHECK(crc32(text.data() + k, text.size() - k, crc32(text.data(), k)) == whole);
    }
}

TEST_CASE("crc32: a real #BESTPOSA line's stated CRC")
{
    const auto body = bytes(
        "BESTPOSA,COM1,0,65.5,FINESTEERING,1687,419928.000,00000000,6145,3153;SOL_COMPUTED,SINGLE,32.59535912622,"
        "-85.29567789741,199.9777,-29.2000,WGS84,1.1396,1.1687,2.4308,\"\",0.000,0.000,12,12,0,0,0,06,00,03");
    CHECK(crc32(body.data(), body.size()) == 0x49329266U);
}

TEST_CASE("nmea_checksum: the empty no-fix GGA and a real GST")
{
    const auto gga = bytes("GPGGA,,,,,,0,,,,,,,,");
    CHECK(nmea_checksum(gga.data(), gga.size()) == 0x66);
    const auto gst = bytes("GPGST,112257.00,0.387,317.719,3.872,1.791,317.563,10.659,180.746");
    CHECK(nmea_checksum(gst.data(), gst.size()) == 0x61);
}

TEST_CASE("parse_hex: both cases, rejects non-hex")
{
    uint32_t v = 0;
    const auto lower = bytes("49329266");
    REQUIRE(parse_hex(lower.data(), 8, v));
    CHECK(v == 0x49329266U);
    const auto upper = bytes("aBcD");
    REQUIRE(parse_hex(upper.data(), 4, v));
    CHECK(v == 0xABCDU);
    const auto bad = bytes("12g4");
    CHECK_FALSE(parse_hex(bad.data(), 4, v));
}
