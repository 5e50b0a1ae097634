// The emulator's logic (tools/sim/imu/imu_emulator.cpp): its answers decode with the driver's
// codec to what it was configured with; confirmations, streaming schedule, faults.
#include <catch2/catch.hpp>

#include <cmath>

#include "imu_emulator.hpp"
#include "ugv/microstrain_gx1/frame_parser.hpp"

using namespace ugv::microstrain_gx1;
using ugv::sim::imu::EmulatorConfig;
using ugv::sim::imu::Gx1Emulator;

namespace {

std::vector<Frame> drain(Gx1Emulator& emu)
{
    FrameParser p;
    std::vector<uint8_t> bytes(emu.output().begin(), emu.output().end());
    emu.output().clear();
    p.feed(bytes.data(), bytes.size());
    std::vector<Frame> out;
    Frame f;
    while (p.next(f)) out.push_back(f);
    return out;
}

void send(Gx1Emulator& emu, const std::vector<uint8_t>& bytes, double t) { emu.receive(bytes.data(), bytes.size(), t); }

}  // namespace

TEST_CASE("emulator: identity, EEPROM read and write, gains", "[gx1][emulator]")
{
    EmulatorConfig ec;
    ec.serial_number = 77;
    ec.accel_gain_scale = 8123;
    Gx1Emulator emu(ec);
    send(emu, encode_simple(0xF1), 0.1);
    send(emu, encode_read_eeprom(230), 0.1);
    send(emu, encode_read_eeprom(246), 0.1);
    auto frames = drain(emu);
    REQUIRE(frames.size() == 3);
    CHECK(frames[0].command == 0xF1);
    CHECK(frames[0].words[0] == 77);
    CHECK(frames[1].words[0] == 8123);
    CHECK(frames[2].words[0] == 1);  // timing word 246 of 16/16/256/1

    // A write with the right confirmation bytes takes; a wrong one is ignored.
    send(emu, encode_write_eeprom(246, 2), 0.2);
    auto bad = encode_write_eeprom(240, 99);
    bad.back() = 0x55;
    send(emu, bad, 0.2);
    send(emu, encode_read_eeprom(240), 0.2);
    frames = drain(emu);
    REQUIRE(frames.size() == 2);
    CHECK(frames[0].command == 0x29);
    CHECK(frames[1].words[0] == 16);
    CHECK(emu.tick_period_s() == Approx(2 * 6.5536e-3));

    send(emu, encode_write_gains(1, 2, 3), 0.3);
    send(emu, encode_simple(0x25), 0.3);
    frames = drain(emu);
    REQUIRE(frames.size() == 2);
    CHECK(frames[1].words[0] == 1);
    CHECK(frames[1].words[2] == 3);
}

TEST_CASE("emulator: commands split over writes, tare confirmation", "[gx1][emulator]")
{
    Gx1Emulator emu{EmulatorConfig{}};
    const auto read = encode_read_eeprom(130);
    for (uint8_t b : read) emu.receive(&b, 1, 0.5);
    auto bad_tare = encode_tare();
    bad_tare[2] = 0x00;
    send(emu, bad_tare, 0.5);
    send(emu, encode_tare(), 0.5);
    const auto frames = drain(emu);
    REQUIRE(frames.size() == 2);
    CHECK(frames[0].words[0] == 10000);
    CHECK(frames[1].command == 0x0F);
}

TEST_CASE("emulator: timer ticks and the continuous schedule", "[gx1][emulator]")
{
    EmulatorConfig ec;
    ec.timing.words = {4, 10, 250, 10};  // 10 ms
    ec.rate_hz = 25;                     // 4 ticks
    ec.clock_ppm = 0;
    Gx1Emulator emu(ec, 100.0);
    CHECK(emu.ticks_at(100.0) == 0);
    CHECK(emu.ticks_at(101.0) == 100);
    send(emu, encode_start_continuous(0x0E), 101.0);
    emu.advance(102.0);
    auto frames = drain(emu);
    REQUIRE(frames.size() == 26);  // the echo + 25 frames in one second
    CHECK(frames[0].command == 0x10);
    CHECK((frames[0].words[0] & 0xFF) == 0x0E);
    for (std::size_t i = 2; i < frames.size(); ++i) {
        CHECK(frames[i].command == 0x0E);
        CHECK(frames[i].ticks() - frames[i - 1].ticks() == 4);
    }
    send(emu, encode_stop_continuous(), 102.0);
    emu.advance(103.0);
    frames = drain(emu);
    REQUIRE(frames.size() == 1);
    CHECK_FALSE(emu.streaming());
}

TEST_CASE("emulator: attitude in device convention, silence and garbage", "[gx1][emulator]")
{
    EmulatorConfig ec;
    ec.attitude = ugv::sim::imu::fixed_attitude(0.1, -0.2, 1.0);
    Gx1Emulator emu(ec);
    send(emu, encode_simple(0x0E), 1.0);
    auto frames = drain(emu);
    REQUIRE(frames.size() == 1);
    const auto s = decode_sample(frames[0], GainScales{});
    CHECK(s.roll_rad == Approx(0.1).margin(1e-4));
    CHECK(s.pitch_rad == Approx(-0.2).margin(1e-4));
    CHECK(s.yaw_rad == Approx(1.0).margin(1e-4));

    emu.set_silent(true);
    send(emu, encode_simple(0x0E), 2.0);
    CHECK(emu.output().empty());
    emu.set_silent(false);
    emu.inject_garbage(100);
    CHECK(emu.output().size() == 100);
}

TEST_CASE("emulator: every n-th streamed frame cut short, the rest whole", "[gx1][emulator]")
{
    EmulatorConfig ec;
    ec.timing.words = {4, 10, 250, 10};  // 10 ms
    ec.rate_hz = 25;                     // 4 ticks
    Gx1Emulator emu(ec, 100.0);
    emu.set_truncate_every(5);
    send(emu, encode_start_continuous(0x0E), 101.0);
    emu.advance(102.0);
    CHECK(emu.counters().frames_streamed == 25);
    CHECK(emu.counters().frames_truncated == 5);
    // 1 echo + 25 frames of 11 bytes, five of them cut to 1..10 bytes.
    CHECK(emu.output().size() < 7 + 25 * 11);
    CHECK(emu.output().size() >= 7 + 20 * 11 + 5);
    auto frames = drain(emu);
    REQUIRE(frames.size() == 1 + 20);  // the parser finds every whole one after a cut one
    // Frames 5, 10, 15, 20, 25 are missing: the ticks jump by 8 after every fourth.
    int jumps = 0;
    for (std::size_t i = 2; i < frames.size(); ++i) {
        const int step = frames[i].ticks() - frames[i - 1].ticks();
        CHECK((step == 4 || step == 8));
        jumps += step == 8;
    }
    CHECK(jumps == 4);  // the fifth missing frame is the last one
}
