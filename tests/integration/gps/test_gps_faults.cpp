// ugv-gps against `ugv-sim gps` with line faults (issue 11, device faults), real LCM on ports
// 7757-7763: bit errors at 1e-3 and 1e-2 per byte (binary and NMEA), truncated frames, a receiver left at
// another baud (configure mode finds it by probing; passive mode says which rate it listens
// at and recovers once the rates match). The emulator runs without noise, so every fix the
// daemon publishes must be its exact position: a corrupted fix that got through would not.
#include <catch2/catch.hpp>

#include <cmath>
#include <csignal>
#include <mutex>
#include <string>
#include <vector>

#include "gps_rig.hpp"

using ugv::test::gps::check_position;
using ugv::test::gps::Listener;
using ugv::test::gps::Rig;

namespace {

constexpr int8_t kRunning = ugv::daemon_status_t::STATE_RUNNING;
constexpr int8_t kDegraded = ugv::daemon_status_t::STATE_DEGRADED;

// BESTPOSB at 10 Hz (104-byte frames); a generous silence timeout so that a run of damaged
// frames at 1e-2 is not taken for a dead receiver.
const std::string kBinary10Hz = "mode = \"configure\"\nprotocol = \"novatel\"\nlogs = [\"BESTPOSB 0.1\"]\n"
                                "silence_timeout_s = 2.0\n";

bool state_now(Listener& l, int8_t state)
{
    std::lock_guard<std::mutex> g(l.t.m);
    return !l.t.status.empty() && l.t.status.back().state == state;
}

std::string last_error(Listener& l)
{
    std::lock_guard<std::mutex> g(l.t.m);
    return l.t.status.empty() ? std::string() : l.t.status.back().last_error;
}

// Every fix so far is the emulator's position, SINGLE.
void check_every_fix_exact(Listener& l)
{
    std::lock_guard<std::mutex> g(l.t.m);
    for (const auto& f : l.t.fixes) {
        INFO("fix seq " << f.seq);
        check_position(f);
        CHECK(f.fix_quality == ugv::gps_fix_t::QUALITY_SINGLE);
    }
}

void stop_cleanly(Rig& rig)
{
    CHECK(rig.daemon->running());
    rig.daemon->signal(SIGTERM);
    CHECK(rig.daemon->wait_exit(5.0) == 0);
    rig.daemon.reset();
}

}  // namespace

TEST_CASE("ugv-gps: bit errors at 1e-3 and 1e-2 per byte are counted, never published")
{
    // A 104-byte BESTPOSB survives 1e-3 with p = 0.90 and 1e-2 with p = 0.35; command
    // replies are damaged too, so some configurations fail and are retried.
    const auto run = [](int port, const std::string& rate, std::size_t want_fixes) {
        Listener l(port);
        Rig rig;
        rig.start_sim({"--protocol", "novatel", "--bit-error-rate", rate, "--seed", "5"});
        rig.start_daemon(kBinary10Hz, port);
        INFO("bit error rate " << rate << "\n" << rig.logs());
        REQUIRE(l.wait([&] { return l.t.nfix() >= want_fixes; }, 30.0));
        REQUIRE(l.wait([&] { return l.t.counter("crc_errors") > 0 && state_now(l, kRunning); }, 10.0));
        check_every_fix_exact(l);
        CHECK(l.t.counter("malformed") == 0);
        stop_cleanly(rig);
    };
    SECTION("1e-3") { run(7757, "0.001", 40); }
    SECTION("1e-2") { run(7758, "0.01", 20); }
}

TEST_CASE("ugv-gps, NMEA: bit errors at 1e-3 and 1e-2; a wrong fix only where the damage kept the checksum")
{
    // NMEA's checksum is an XOR: two flips of one bit in a sentence cancel (~3 % of 70-byte
    // GGA sentences at 1e-2). The emulator counts the damaged sentences whose checksum still
    // holds; the daemon cannot see those, so that many wrong (or malformed) fixes are allowed,
    // and no more.
    const auto run = [](int port, const std::string& rate, std::size_t want_fixes) {
        Listener l(port);
        Rig rig;
        rig.start_sim({"--protocol", "nmea", "--bit-error-rate", rate, "--seed", "7"});
        rig.start_daemon("mode = \"configure\"\nprotocol = \"nmea\"\nperiod_s = 0.1\nsilence_timeout_s = 2.0\n", port);
        INFO("bit error rate " << rate << "\n" << rig.logs());
        REQUIRE(l.wait([&] { return l.t.nfix() >= want_fixes; }, 40.0));
        REQUIRE(l.wait([&] { return l.t.counter("crc_errors") > 0; }, 10.0));
        stop_cleanly(rig);
        rig.sim->signal(SIGTERM);
        REQUIRE(rig.sim->wait_exit(5.0) == 0);
        const std::string summary = rig.sim->err();
        const std::size_t at = summary.find(" NMEA sentences damaged unseen");
        REQUIRE(at != std::string::npos);
        const std::size_t from = summary.rfind(' ', at - 1) + 1;
        const int unseen = std::stoi(summary.substr(from, at - from));
        int wrong = 0, total = 0;
        {
            std::lock_guard<std::mutex> g(l.t.m);
            for (const auto& f : l.t.fixes) {
                ++total;
                wrong += std::fabs(f.latitude - ugv::test::gps::kLat) > 1e-7 ||
                         std::fabs(f.longitude - ugv::test::gps::kLon) > 1e-7 ||
                         std::fabs(f.height - (750.0 - 17.0)) > 1e-3;
            }
        }
        INFO(total << " fixes, " << wrong << " wrong, " << unseen << " sentences damaged with a valid checksum");
        // A damaged sentence the checksum passes comes out as a wrong fix, or, when its values
        // are impossible (a latitude of 401 deg), is counted malformed: either way one of them.
        const auto malformed = static_cast<int>(l.t.counter("malformed"));
        CHECK(wrong + malformed <= unseen);
    };
    SECTION("1e-3") { run(7762, "0.001", 60); }
    SECTION("1e-2") { run(7763, "0.01", 40); }
}

TEST_CASE("ugv-gps: truncated frames are counted and dropped, the stream goes on")
{
    Listener l(7759);
    Rig rig;
    rig.start_sim({"--protocol", "novatel", "--truncate-probability", "0.2", "--seed", "6"});
    rig.start_daemon("mode = \"configure\"\nprotocol = \"novatel\"\nlogs = [\"BESTPOSB 0.1\", \"BESTVELB 0.1\"]\n"
                     "silence_timeout_s = 2.0\n",
                     7759);
    INFO(rig.logs());
    REQUIRE(l.wait([&] { return l.t.nfix() >= 40; }, 30.0));
    // A cut frame claims its full length; once the next frame has arrived the CRC fails and
    // the splitter finds that next frame inside the rejected bytes.
    REQUIRE(l.wait([&] {
        return l.t.counter("crc_errors") + l.t.counter("bad_length") > 5 && state_now(l, kRunning);
    }, 10.0));
    check_every_fix_exact(l);
    {
        std::lock_guard<std::mutex> g(l.t.m);
        REQUIRE_FALSE(l.t.vels.empty());
        for (const auto& v : l.t.vels) CHECK(v.horizontal_speed == 0.0);
    }
    CHECK(l.t.counter("malformed") == 0);
    CHECK(l.t.counter("reconnects") == 0);
    stop_cleanly(rig);
}

TEST_CASE("ugv-gps configure mode: a receiver left at 115200 is found by probing and set back to 9600")
{
    Listener l(7760);
    Rig rig;
    rig.start_sim({"--protocol", "novatel", "--baud", "115200"});
    rig.start_daemon(kBinary10Hz + "reply_timeout_ms = 300\n", 7760);
    INFO(rig.logs());
    REQUIRE(l.wait([&] { return l.t.nfix() >= 20; }, 30.0));
    REQUIRE(l.wait([&] { return l.t.counter("found_by_probing") == 1 && state_now(l, kRunning); }, 10.0));
    CHECK(rig.daemon->err().find("receiver answered at 115200 baud, not at the configured 9600") != std::string::npos);
    // Found on the first start: no failed configuration, no reconnect.
    CHECK(l.t.counter("configure_failures") == 0);
    CHECK(l.t.counter("reconnects") == 0);
    check_every_fix_exact(l);
    stop_cleanly(rig);
}

TEST_CASE("ugv-gps passive mode at the wrong baud: DEGRADED naming the rate, nothing published, recovers")
{
    Listener l(7761);
    Rig rig;
    rig.start_sim({"--protocol", "novatel", "--baud", "115200", "--preconfigured", "--rate-hz", "10"});
    rig.start_daemon("mode = \"passive\"\nsilence_timeout_s = 1.0\n", 7761);
    INFO(rig.logs());
    // Bytes arrive (noise at the wrong rate), never a frame.
    REQUIRE(l.wait([&] { return l.t.counter("silences") >= 1 && state_now(l, kDegraded); }, 20.0));
    CHECK(last_error(l).find("no valid frame for 1000 ms at 9600 baud") != std::string::npos);
    CHECK(l.t.counter("skipped_bytes") > 0);
    CHECK(l.t.nfix() == 0);
    // Someone sets the receiver to 9600 (here: a receiver at 9600 on the same port).
    rig.sim->signal(SIGTERM);
    CHECK(rig.sim->wait_exit(5.0) == 0);
    rig.start_sim({"--protocol", "novatel", "--baud", "9600", "--preconfigured", "--rate-hz", "10"});
    REQUIRE(l.wait([&] { return l.t.nfix() >= 10 && state_now(l, kRunning); }, 20.0));
    check_every_fix_exact(l);
    stop_cleanly(rig);
}
