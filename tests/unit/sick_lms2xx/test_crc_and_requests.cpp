// Known-answer vectors from shared/protocols/sick-lms2xx.md: every request the session sends
// is checked byte for byte, CRC included.
#include <catch2/catch.hpp>

#include <vector>

#include "ugv/sick_lms2xx/crc.hpp"
#include "ugv/sick_lms2xx/requests.hpp"
#include "ugv/sick_lms2xx/telegram.hpp"

using namespace ugv::sick_lms2xx;
using Bytes = std::vector<uint8_t>;

TEST_CASE("crc16 of the fact sheet vectors", "[sick_lms2xx][crc]")
{
    const Bytes start = {0x02, 0x00, 0x02, 0x00, 0x20, 0x24};
    CHECK(crc16(start.data(), start.size()) == 0x0834);
    const Bytes variant = {0x02, 0x00, 0x05, 0x00, 0x3B, 0xB4, 0x00, 0x32, 0x00};
    CHECK(crc16(variant.data(), variant.size()) == 0x1F3B);
    CHECK(crc16(nullptr, 0) == 0);
}

TEST_CASE("requests match the known-answer telegrams", "[sick_lms2xx][requests]")
{
    CHECK(request_installation_mode() ==
          Bytes{0x02, 0x00, 0x0A, 0x00, 0x20, 0x00, 0x53, 0x49, 0x43, 0x4B, 0x5F, 0x4C, 0x4D, 0x53, 0xBE, 0xC5});
    CHECK(request_start_streaming() == Bytes{0x02, 0x00, 0x02, 0x00, 0x20, 0x24, 0x34, 0x08});
    CHECK(request_stop_streaming() == Bytes{0x02, 0x00, 0x02, 0x00, 0x20, 0x25, 0x35, 0x08});
    CHECK(request_baud(500000) == Bytes{0x02, 0x00, 0x02, 0x00, 0x20, 0x48, 0x58, 0x08});
    CHECK(request_baud(38400) == Bytes{0x02, 0x00, 0x02, 0x00, 0x20, 0x40, 0x50, 0x08});
    CHECK(request_variant(180, 50) == Bytes{0x02, 0x00, 0x05, 0x00, 0x3B, 0xB4, 0x00, 0x32, 0x00, 0x3B, 0x1F});
}

TEST_CASE("request framing: mode bytes, commands and lengths", "[sick_lms2xx][requests]")
{
    CHECK(baud_mode_byte(9600) == uint8_t{0x42});
    CHECK(baud_mode_byte(19200) == uint8_t{0x41});
    CHECK(baud_mode_byte(38400) == uint8_t{0x40});
    CHECK(baud_mode_byte(500000) == uint8_t{0x48});
    CHECK_FALSE(baud_mode_byte(115200).has_value());
    CHECK_THROWS(request_baud(115200));
    CHECK_THROWS(request_variant(90, 50));
    CHECK_THROWS(request_variant(180, 33));

    const auto check_frame = [](const Bytes& t, uint8_t command, std::size_t data_len) {
        REQUIRE(t.size() == 4 + 1 + data_len + 2);
        CHECK(t[0] == 0x02);
        CHECK(t[1] == 0x00);
        CHECK(get_u16le(t.data() + 2) == 1 + data_len);
        CHECK(t[4] == command);
        CHECK(get_u16le(t.data() + t.size() - 2) == crc16(t.data(), t.size() - 2));
    };
    check_frame(request_baud(9600), 0x20, 1);
    CHECK(request_baud(9600)[5] == 0x42);
    check_frame(request_baud(19200), 0x20, 1);
    CHECK(request_baud(19200)[5] == 0x41);
    check_frame(request_type(), 0x3A, 0);
    check_frame(request_status(), 0x31, 0);
    check_frame(request_read_config(), 0x74, 0);
    check_frame(request_reset(), 0x10, 0);
    const Bytes block(32, 0x11);
    check_frame(request_write_config(block), 0x77, 32);
    check_frame(request_variant(100, 25), 0x3B, 4);
    CHECK(request_variant(100, 25)[5] == 100);
    CHECK(request_variant(100, 25)[7] == 25);
    check_frame(request_installation_mode("WRONGPWD"), 0x20, 9);
}

TEST_CASE("a reply telegram counts its status byte in LEN", "[sick_lms2xx][telegram]")
{
    const Bytes data = {0x00};
    const Bytes reply = encode_reply(0xA0, data, 0x10);
    REQUIRE(reply.size() == 4 + 3 + 2);
    CHECK(reply[1] == 0x80);
    CHECK(get_u16le(reply.data() + 2) == 3);
    CHECK(reply[4] == 0xA0);
    CHECK(reply[6] == 0x10);
    CHECK(reply_command(0x3B) == 0xBB);
    CHECK(reply_command(0x74) == 0xF4);
    CHECK(cmd::reset_reply == 0x91);  // the one reply that is not CMD | 0x80
    CHECK_THROWS(encode_reply(0xB0, Bytes(812, 0), 0));  // 1 + 812 + 1 > 812
    CHECK_NOTHROW(encode_reply(0xB0, Bytes(810, 0), 0));
}
