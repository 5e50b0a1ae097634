// The session against the receiver emulator through an in-memory byte stream.
#include <catch2/catch.hpp>

#include <variant>

#include "emulator_stream.hpp"
#include "ugv/io/clock.hpp"
#include "ugv/novatel/session.hpp"

using namespace ugv::novatel;
using ugv::novatel::test::EmulatorStream;
using ugv::sim::gps::EmulatorConfig;
using ugv::sim::gps::GpsEmulator;

namespace {

struct Received
{
    int positions = 0;
    int velocities = 0;
    int ggas = 0;
    Decoder::Sink sink()
    {
        return [this](const Decoded& d) {
            if (std::holds_alternative<Position>(d.message)) ++positions;
            if (std::holds_alternative<Velocity>(d.message)) ++velocities;
            if (std::holds_alternative<Gga>(d.message)) ++ggas;
        };
    }
};

// Polls until the predicate holds or timeout_s passes (generous: a loaded machine).
template <typename Pred>
bool poll_until(Session& s, Received& r, Pred pred, double timeout_s = 5.0)
{
    const int64_t end = ugv::io::monotonic_us() + static_cast<int64_t>(timeout_s * 1e6);
    while (!pred() && ugv::io::monotonic_us() < end) {
        if (s.poll(20, r.sink()) == Session::Status::closed) {
            return false;
        }
    }
    return pred();
}

SessionConfig configure_logs(std::vector<LogRequest> logs)
{
    SessionConfig c;
    c.configure = true;
    c.logs = std::move(logs);
    c.reply_timeout_ms = 500;
    return c;
}

}  // namespace

TEST_CASE("session configure: UNLOGALL + LOGs answered <OK, then BESTPOSB/BESTVELB flow at the logged rate")
{
    EmulatorConfig ec;
    ec.noise_scale = 0;
    GpsEmulator emu(ec, ugv::io::now_utime());
    EmulatorStream stream(emu, 9600);
    Decoder decoder;
    Session session(stream, decoder, configure_logs({{"bestposb", 0.05}, {"bestvelb", 0.05}}));
    Received r;
    REQUIRE(session.start(r.sink()));
    CHECK(session.counters().commands_sent == 3);
    CHECK(session.counters().commands_failed == 0);
    CHECK(emu.active_logs() == 2);
    CHECK(poll_until(session, r, [&] { return r.positions >= 5 && r.velocities >= 5; }));
    CHECK(decoder.splitter_counters().crc_errors == 0);
}

TEST_CASE("session configure: an <ERROR reply fails the start and says which command")
{
    GpsEmulator emu(EmulatorConfig{}, ugv::io::now_utime());
    EmulatorStream stream(emu, 9600);
    Decoder decoder;
    Session session(stream, decoder, configure_logs({{"rangecmpb", 1.0}}));
    Received r;
    REQUIRE_FALSE(session.start(r.sink()));
    CHECK(session.error().find("LOG RANGECMPB ONTIME 1") != std::string::npos);
    CHECK(session.error().find("ERROR") != std::string::npos);
    CHECK(session.counters().commands_failed == 1);
}

TEST_CASE("session configure: COM switches receiver and host; a restart finds the receiver at the new rate")
{
    EmulatorConfig ec;
    GpsEmulator emu(ec, ugv::io::now_utime());
    EmulatorStream stream(emu, 9600);
    Decoder decoder;
    auto cfg = configure_logs({{"bestposb", 0.05}});
    cfg.com_baud = 115200;
    Received r;
    {
        Session session(stream, decoder, cfg);
        REQUIRE(session.start(r.sink()));
        CHECK(emu.baud() == 115200);
        CHECK(stream.baud() == 115200);
        CHECK(poll_until(session, r, [&] { return r.positions >= 3; }));
    }
    // The host reopens the port at its configured 9600; the receiver stayed at 115200.
    stream.set_baud(9600);
    Session again(stream, decoder, cfg);
    REQUIRE(again.start(r.sink()));
    CHECK(stream.baud() == 115200);
    const int before = r.positions;
    CHECK(poll_until(again, r, [&] { return r.positions >= before + 3; }));
}

TEST_CASE("session configure: a receiver left at another rate is found by probing and set back with COM")
{
    EmulatorConfig ec;
    ec.baud = 57600;
    ec.noise_scale = 0;
    GpsEmulator emu(ec, ugv::io::now_utime());
    EmulatorStream stream(emu, 9600);
    Decoder decoder;
    auto cfg = configure_logs({{"bestposb", 0.05}});
    cfg.reply_timeout_ms = 200;
    cfg.probe_bauds = {9600, 19200, 57600, 115200};
    Session session(stream, decoder, cfg);
    Received r;
    REQUIRE(session.start(r.sink()));
    CHECK(session.found_at_baud() == 57600);
    CHECK(session.counters().found_by_probing == 1);
    // Both sides back at the configured rate, and the logs flow there.
    CHECK(emu.baud() == 9600);
    CHECK(stream.baud() == 9600);
    // UNLOGALL twice at 9600, at 19200, at 57600 (answered), COM 9600, LOG.
    CHECK(session.counters().commands_sent == 6);
    CHECK(poll_until(session, r, [&] { return r.positions >= 3; }));
}

TEST_CASE("session configure: no answer at any rate names the configured rate and the probed ones")
{
    EmulatorConfig ec;
    ec.baud = 38400;
    GpsEmulator emu(ec, ugv::io::now_utime());
    EmulatorStream stream(emu, 9600);
    Decoder decoder;
    auto cfg = configure_logs({{"bestposb", 0.05}});
    cfg.reply_timeout_ms = 100;
    cfg.probe_bauds = {19200, 115200};
    Session session(stream, decoder, cfg);
    Received r;
    REQUIRE_FALSE(session.start(r.sink()));
    CHECK(session.error() == "UNLOGALL: no reply at the configured 9600 baud (nor at 19200, 115200)");
    CHECK(session.found_at_baud() == 0);
    CHECK(stream.baud() == 9600);  // left where it was opened
    CHECK(r.positions == 0);
}

TEST_CASE("session passive: sends nothing and reads a receiver configured by someone else (NMEA)")
{
    EmulatorConfig ec;
    ec.protocol = ugv::sim::gps::Protocol::nmea;
    ec.preconfigured = true;
    ec.rate_hz = 20;
    GpsEmulator emu(ec, ugv::io::now_utime());
    EmulatorStream stream(emu, 9600);
    Decoder decoder;
    SessionConfig cfg;
    cfg.configure = false;
    Session session(stream, decoder, cfg);
    Received r;
    REQUIRE(session.start(r.sink()));
    CHECK(poll_until(session, r, [&] { return r.ggas >= 5; }));
    CHECK(emu.commands_received() == 0);
}

TEST_CASE("session: silence beyond the timeout is reported; a closed device is reported")
{
    EmulatorConfig ec;
    ec.preconfigured = true;
    ec.rate_hz = 20;
    ec.silence_at_s = 0.0;
    ec.silence_for_s = 100.0;
    GpsEmulator emu(ec, ugv::io::now_utime());
    EmulatorStream stream(emu, 9600);
    Decoder decoder;
    SessionConfig cfg;
    cfg.configure = false;
    cfg.silence_timeout_us = 300'000;
    Session session(stream, decoder, cfg);
    Received r;
    REQUIRE(session.start(r.sink()));
    Session::Status st = Session::Status::ok;
    const int64_t end = ugv::io::monotonic_us() + 5'000'000;
    while (st == Session::Status::ok && ugv::io::monotonic_us() < end) {
        st = session.poll(20, r.sink());
    }
    CHECK(st == Session::Status::silent);
    CHECK(r.positions == 0);
    stream.close();
    CHECK(session.poll(20, r.sink()) == Session::Status::closed);
}
