#include <catch2/catch.hpp>

#include <string>

#include "frame_helpers.hpp"
#include "ugv/canopen/emcy.hpp"

using namespace ugv::canopen;
using canopen_test::frame;
using canopen_test::text;

TEST_CASE("EMCY decoding: code, error register, manufacturer bytes")
{
    auto e = decode_emcy(frame("082#1186080102030405"), 2);
    REQUIRE(e);
    CHECK(e->error_code == 0x8611);
    CHECK(e->error_register == 0x08);
    CHECK(e->manufacturer == std::array<uint8_t, 5>{1, 2, 3, 4, 5});
    CHECK_FALSE(e->is_reset());
    CHECK(std::string(describe_emcy(0x8611)) == "following error");
    CHECK(std::string(describe_emcy(0x2311)) == "current");
    e = decode_emcy(frame("082#0000000000000000"), 2);
    REQUIRE(e);
    CHECK(e->is_reset());
    CHECK_FALSE(decode_emcy(frame("080#"), 0));          // SYNC
    CHECK_FALSE(decode_emcy(frame("083#1186080102030405"), 2));
    CHECK(text(encode_emcy(2, Emergency{0x7300, 0x01, {}})) == "082#0073010000000000");
}
