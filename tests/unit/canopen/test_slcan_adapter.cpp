#include <catch2/catch.hpp>

#include <string>

#include "slcan_adapter.hpp"

using ugv::sim::servo::SlcanAdapter;

namespace {
std::vector<ugv::io::CanFrame> feed(SlcanAdapter& a, const std::string& s)
{
    return a.feed(reinterpret_cast<const uint8_t*>(s.data()), s.size(), 0);
}
}  // namespace

TEST_CASE("slcan adapter: bitrate, open, transmit with z acknowledgement, close")
{
    SlcanAdapter a;
    CHECK(feed(a, "t60282B40600006000000\r").empty());  // not open: BEL
    CHECK(a.take_output() == "\a");
    feed(a, "O\r");                                    // no bitrate yet: BEL
    CHECK(a.take_output() == "\a");
    feed(a, "S6\rO\r");
    CHECK(a.take_output() == "\r\r");
    CHECK(a.bitrate_code() == 6);
    feed(a, "S4\r");  // bitrate only while closed
    CHECK(a.take_output() == "\a");
    const auto frames = feed(a, "t60282B40600006000000\rT12ABCDEF2AA55\r");
    REQUIRE(frames.size() == 2);
    CHECK(frames[0].id == 0x602);
    CHECK(frames[0].dlc == 8);
    CHECK(frames[0].data[0] == 0x2B);
    CHECK(frames[1].extended);
    CHECK(frames[1].id == 0x12ABCDEF);
    CHECK(a.take_output() == "z\rZ\r");
    ugv::io::CanFrame hb;
    hb.id = 0x702;
    hb.dlc = 1;
    hb.data[0] = 0x05;
    a.on_bus_frame(hb, 0);
    CHECK(a.take_output() == "t702105\r");
    feed(a, "C\r");
    CHECK(a.take_output() == "\r");
    a.on_bus_frame(hb, 0);
    CHECK(a.take_output().empty());  // closed: nothing reaches the host
}

TEST_CASE("slcan adapter: split input, time stamps, status, malformed frames")
{
    SlcanAdapter a;
    feed(a, "S");
    feed(a, "8\rZ1");
    feed(a, "\rO\r");
    CHECK(a.take_output() == "\r\r\r");
    ugv::io::CanFrame f;
    f.id = 0x182;
    f.dlc = 2;
    f.data[0] = 0x37;
    f.data[1] = 0x02;
    a.on_bus_frame(f, 61'234'000);  // 61234 ms -> 1234 ms after the 60000 wrap = 0x04D2
    CHECK(a.take_output() == "t18223702" "04D2\r");
    feed(a, "F\r");
    CHECK(a.take_output() == "F00\r");
    feed(a, "t60\r");  // truncated
    CHECK(a.take_output() == "\a");
    CHECK(a.errors() == 1);
}

TEST_CASE("slcan adapter: bus-off answers BEL and stays silent until closed and reopened")
{
    SlcanAdapter a;
    feed(a, "S6\rO\r");
    a.take_output();
    a.bus_off();
    CHECK(a.take_output() == "\a");
    ugv::io::CanFrame hb;
    hb.id = 0x702;
    hb.dlc = 1;
    a.on_bus_frame(hb, 0);
    CHECK(a.take_output().empty());
    CHECK(feed(a, "t702100\r").empty());
    CHECK(a.take_output() == "\a");
    feed(a, "C\rS6\rO\r");
    CHECK(a.take_output() == "\r\r\r");
    CHECK_FALSE(a.is_bus_off());
    CHECK(feed(a, "t702100\r").size() == 1);
}
