#include <catch2/catch.hpp>

#include <string>

#include "serial_line_faults.hpp"
#include "slcan_adapter.hpp"
#include "ugv/io/slcan_codec.hpp"

using ugv::sim::servo::SlcanAdapter;

namespace {
std::vector<ugv::io::CanFrame> feed(SlcanAdapter& a, const std::string& s)
{
    return a.feed(reinterpret_cast<const uint8_t*>(s.data()), s.size(), 0);
}
// A heartbeat of the node in NMT state `state`, as the drive puts it on the bus.
ugv::io::CanFrame heartbeat(uint32_t node, uint8_t state)
{
    ugv::io::CanFrame hb;
    hb.id = 0x700 + node;
    hb.dlc = 1;
    hb.data[0] = state;
    return hb;
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
    const auto hb = heartbeat(2, 0x05);
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
    const auto hb = heartbeat(2, 0x00);
    a.on_bus_frame(hb, 0);
    CHECK(a.take_output().empty());
    CHECK(feed(a, "t702100\r").empty());
    CHECK(a.take_output() == "\a");
    feed(a, "C\rS6\rO\r");
    CHECK(a.take_output() == "\r\r\r");
    CHECK_FALSE(a.is_bus_off());
    CHECK(feed(a, "t702100\r").size() == 1);
}

TEST_CASE("slcan adapter faults: a bus at another bitrate passes nothing; every n-th transmit refused with BEL")
{
    SlcanAdapter a;
    a.set_bus_bitrate_code(5);  // the bus runs at 250 kbit/s
    feed(a, "S6\rO\r");         // the host sets 500 kbit/s
    CHECK(a.take_output() == "\r\r");
    CHECK(feed(a, "t60282B40600006000000\r").empty());  // queued (acknowledged), never on the bus
    CHECK(a.take_output() == "z\r");
    const auto hb = heartbeat(3, 0x00);
    a.on_bus_frame(hb, 0);
    CHECK(a.take_output().empty());
    feed(a, "C\rS5\rO\r");  // now matching
    a.take_output();
    CHECK(feed(a, "t60282B40600006000000\r").size() == 1);
    a.on_bus_frame(hb, 0);
    CHECK(a.take_output() == "z\rt703100\r");

    SlcanAdapter r;
    r.set_refuse_tx_every(3);
    feed(r, "S6\rO\r");
    r.take_output();
    std::size_t sent = 0;
    for (int i = 0; i < 6; ++i) sent += feed(r, "t2020\r").size();
    CHECK(sent == 4);
    CHECK(r.take_output() == "z\rz\r\az\rz\r\a");
    CHECK(r.tx_refused() == 2);
}

TEST_CASE("line faults: bit errors damage one bit of a byte at the given rate, reproducibly")
{
    ugv::sim::servo::SerialLineFaultConfig c;
    c.bit_error_rate = 0.01;
    c.seed = 42;
    ugv::sim::servo::SerialLineFaults faults(c), same(c);
    std::string lines;
    for (int i = 0; i < 5000; ++i) lines += "t1836370602000000\r";  // 90000 bytes
    const std::string out = faults.apply(lines, false);
    CHECK(out == same.apply(lines, false));  // seeded
    REQUIRE(out.size() == lines.size());
    std::size_t damaged = 0;
    for (std::size_t i = 0; i < out.size(); ++i) {
        const auto diff = static_cast<uint8_t>(out[i] ^ lines[i]);
        if (diff == 0) continue;
        ++damaged;
        CHECK((diff & (diff - 1)) == 0);  // exactly one bit
    }
    CHECK(damaged == faults.bytes_damaged());
    CHECK(damaged > 800);  // 900 expected, sigma 30
    CHECK(damaged < 1000);
}

TEST_CASE("line faults: truncated frame lines keep their start and CR and never decode; garbage has no BEL")
{
    ugv::sim::servo::SerialLineFaultConfig c;
    c.truncate_every = 2;
    c.garbage_bytes = 500;
    ugv::sim::servo::SerialLineFaults faults(c);
    const std::string lines = "t1836370602000000\rz\rt2834E0000000\rt703105\r";
    const std::string out = faults.apply(lines, false);
    CHECK(faults.lines_truncated() == 1);  // the second frame line
    CHECK(out.substr(0, 20) == "t1836370602000000\rz\r");
    const auto cut = out.substr(20, out.find('\r', 20) - 20);
    CHECK(cut.size() >= 1);
    CHECK(cut.size() < 13);
    CHECK(lines.substr(20, cut.size()) == cut);
    CHECK(ugv::io::slcan::decode_line(cut).kind == ugv::io::slcan::Event::Kind::malformed);
    CHECK(out.substr(out.size() - 8) == "t703105\r");

    const std::string noisy = faults.apply("z\r", true);
    CHECK(faults.garbage_sent() == 500);
    CHECK(noisy.size() == 502);
    CHECK(noisy.find('\a') == std::string::npos);
    CHECK(noisy.substr(500) == "z\r");
}
