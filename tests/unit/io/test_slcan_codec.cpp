#include <catch2/catch.hpp>

#include "ugv/io/slcan_codec.hpp"

using namespace ugv::io;
using Kind = slcan::Event::Kind;

TEST_CASE("slcan encodes standard, extended and RTR frames as Lawicel lines")
{
    CanFrame f;
    f.id = 0x601;
    f.dlc = 8;
    f.data = {0x40, 0x41, 0x60, 0x00, 0x00, 0x00, 0x00, 0x00};
    CHECK(slcan::encode_frame(f) == "t60184041600000000000\r");
    CanFrame e;
    e.id = 0x18FEF100;
    e.extended = true;
    e.dlc = 2;
    e.data[0] = 0xAB;
    e.data[1] = 0x0C;
    CHECK(slcan::encode_frame(e) == "T18FEF1002AB0C\r");
    CanFrame r;
    r.id = 0x701;
    r.rtr = true;
    r.dlc = 1;
    CHECK(slcan::encode_frame(r) == "r7011\r");
    CanFrame nmt;
    nmt.id = 0;
    nmt.dlc = 2;
    nmt.data[0] = 0x01;
    nmt.data[1] = 0x05;
    CHECK(slcan::encode_frame(nmt) == "t00020105\r");
}

TEST_CASE("slcan bitrate commands follow the S0..S8 table")
{
    CHECK(slcan::encode_bitrate(10000) == "S0\r");
    CHECK(slcan::encode_bitrate(125000) == "S4\r");
    CHECK(slcan::encode_bitrate(500000) == "S6\r");
    CHECK(slcan::encode_bitrate(1000000) == "S8\r");
    CHECK_FALSE(slcan::encode_bitrate(333333).has_value());
}

TEST_CASE("slcan decodes lines back into the same frames")
{
    for (const std::string line : {"t60184041600000000000", "T18FEF1002AB0C", "r7011", "t0000", "t18581122334455667788"}) {
        const auto e = slcan::decode_line(line);
        REQUIRE(e.kind == Kind::frame);
        CHECK(slcan::encode_frame(e.frame) == line + "\r");
    }
    const auto stamped = slcan::decode_line("t1812AABB1F40");  // with a 4-digit adapter time stamp
    REQUIRE(stamped.kind == Kind::frame);
    CHECK(stamped.frame.id == 0x181);
    CHECK(stamped.frame.data[1] == 0xBB);
}

TEST_CASE("slcan rejects malformed lines")
{
    for (const std::string bad : {"t60", "t6019", "tXYZ0", "t801200", "x123", "t1812AABBCC", "T2FFFFFFF0"})
        CHECK(slcan::decode_line(bad).kind == Kind::malformed);
}

TEST_CASE("slcan decoder splits a stream at any byte, and reports OK, BEL and tx acks")
{
    const std::string stream = "\rt1812AABB\r\az\rT18FEF1002AB0C\rgarbage-line\rt701101\r";
    for (std::size_t split = 0; split <= stream.size(); ++split) {
        slcan::Decoder d;
        auto a = d.feed(reinterpret_cast<const uint8_t*>(stream.data()), split);
        auto b = d.feed(reinterpret_cast<const uint8_t*>(stream.data()) + split, stream.size() - split);
        a.insert(a.end(), b.begin(), b.end());
        REQUIRE(a.size() == 7);
        CHECK(a[0].kind == Kind::ok);
        CHECK(a[1].kind == Kind::frame);
        CHECK(a[1].frame.id == 0x181);
        CHECK(a[2].kind == Kind::error);
        CHECK(a[3].kind == Kind::tx_ack);
        CHECK(a[4].kind == Kind::frame);
        CHECK(a[4].frame.extended);
        CHECK(a[5].kind == Kind::malformed);
        CHECK(a[6].kind == Kind::frame);
        CHECK(a[6].frame.data[0] == 0x01);
        CHECK(d.malformed() == 1);
    }
}

TEST_CASE("slcan decoder survives a runaway line without a CR")
{
    slcan::Decoder d;
    const std::string junk(500, 'A');
    auto ev = d.feed(reinterpret_cast<const uint8_t*>(junk.data()), junk.size());
    CHECK(ev.empty());
    CHECK(d.malformed() >= 1);
    const std::string good = "\rt1230\r";
    ev = d.feed(reinterpret_cast<const uint8_t*>(good.data()), good.size());
    REQUIRE_FALSE(ev.empty());
    CHECK(ev.back().kind == Kind::frame);
    CHECK(ev.back().frame.id == 0x123);
}
