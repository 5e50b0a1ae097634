// Reply lengths, checksum and command encodings of the 3DM-GX1 fact sheet.
#include <catch2/catch.hpp>

#include "ugv/microstrain_gx1/protocol.hpp"

using namespace ugv::microstrain_gx1;
using Bytes = std::vector<uint8_t>;

TEST_CASE("reply lengths follow the fact sheet table", "[gx1][protocol]")
{
    const std::vector<std::pair<uint8_t, std::size_t>> table = {
        {0x01, 23}, {0x02, 23}, {0x03, 23}, {0x04, 13}, {0x05, 13}, {0x06, 5},  {0x07, 7},
        {0x0A, 23}, {0x0B, 23}, {0x0C, 31}, {0x0D, 11}, {0x0E, 11}, {0x31, 23}, {0x10, 7},
        {0x0F, 5},  {0x11, 5},  {0x24, 5},  {0x25, 11}, {0x28, 7},  {0x29, 7},  {0xF0, 5},
        {0xF1, 5}};
    for (auto [command, length] : table) {
        INFO("command " << int(command));
        CHECK(reply_length(command) == length);
        CHECK(reply_words(command) == (length - 3) / 2);
    }
    int known = 0;
    for (int b = 0; b < 256; ++b) known += is_command(static_cast<uint8_t>(b)) ? 1 : 0;
    CHECK(known == static_cast<int>(table.size()));
    CHECK(reply_length(0x00) == 0);
    CHECK(reply_length(0x55) == 0);
    CHECK(reply_words(0x0C) == max_reply_words);
}

TEST_CASE("only the firmware and serial number replies carry no timer", "[gx1][protocol]")
{
    CHECK_FALSE(reply_has_ticks(0xF0));
    CHECK_FALSE(reply_has_ticks(0xF1));
    CHECK(reply_has_ticks(0x31));
    CHECK(reply_has_ticks(0x06));
    CHECK_FALSE(reply_has_ticks(0x55));
}

TEST_CASE("checksum is echo plus the big-endian words, mod 65536", "[gx1][protocol]")
{
    // 0x0E + 0x0100 + 0xFF00 + 0x4000 + 0x1234 = 0x15242 -> 0x5242
    const Bytes words = {0x01, 0x00, 0xFF, 0x00, 0x40, 0x00, 0x12, 0x34};
    CHECK(checksum(0x0E, words.data(), 4) == 0x5242);
    CHECK(checksum(0xF0, words.data(), 0) == 0x00F0);
    const Bytes reply = encode_reply(0x0E, {0x0100, 0xFF00, 0x4000, 0x1234});
    CHECK(reply == Bytes{0x0E, 0x01, 0x00, 0xFF, 0x00, 0x40, 0x00, 0x12, 0x34, 0x52, 0x42});
}

TEST_CASE("command encodings", "[gx1][protocol]")
{
    CHECK(encode_simple(0x31) == Bytes{0x31});
    CHECK(encode_start_continuous(0x31) == Bytes{0x10, 0x00, 0x31});
    CHECK(encode_stop_continuous() == Bytes{0x10, 0x00, 0x00});
    CHECK(encode_tare() == Bytes{0x0F, 0xC1, 0xC3, 0xC5});
    CHECK(encode_remove_tare() == Bytes{0x11, 0xC1, 0xC3, 0xC5});
    CHECK(encode_read_eeprom(230) == Bytes{0x28, 0x00, 0xE6});
    CHECK(encode_read_eeprom(0x1234) == Bytes{0x28, 0x12, 0x34});
    CHECK(encode_write_eeprom(238, 0x0010) == Bytes{0x29, 0x71, 0x00, 0xEE, 0x00, 0x10, 0xAA});
    CHECK(encode_write_gains(0x0102, 0x0304, 0x0506) == Bytes{0x24, 0x01, 0x02, 0x03, 0x04, 0x05, 0x06});
}
