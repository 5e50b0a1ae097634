// ugv-servo drives the emulated CiA 402 drive (ugv-sim servo) through slcan on a pty: it
// reaches Operation Enabled and nods; a fault raised mid-nod is reset and the nod resumes;
// the counters say so; SIGTERM halts, disables and exits 0.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <functional>
#include <numbers>

#include "ugv/bus/typed.hpp"
#include "ugv/daemon_status_t.hpp"
#include "ugv/servo_command_t.hpp"
#include "ugv/servo_state_t.hpp"
#include "ugv_test/process.hpp"

using namespace ugv;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

struct Watch
{
    std::unique_ptr<bus::Bus> bus;
    std::vector<servo_state_t> states;
    std::vector<daemon_status_t> status;

    explicit Watch(const std::string& url) : bus(bus::open_live(url))
    {
        bus::subscribe<servo_state_t>(*bus, "SERVO_STATE", [this](const std::string&, const servo_state_t& m, int64_t) {
            states.push_back(m);
        });
        bus::subscribe<daemon_status_t>(*bus, "STATUS_SERVO",
                                        [this](const std::string&, const daemon_status_t& m, int64_t) {
                                            status.push_back(m);
                                        });
    }
    // Handles messages until pred() holds or timeout_s passes.
    bool until(const std::function<bool()>& pred, double timeout_s)
    {
        return test::wait_until(
            [&] {
                while (bus->handle(0) == bus::HandleResult::handled) {
                }
                return pred();
            },
            timeout_s);
    }
    // Collects the states published during the next seconds (by their own time stamps).
    std::vector<servo_state_t> collect(double seconds)
    {
        states.clear();
        until([&] { return !states.empty() && static_cast<double>(states.back().utime - states.front().utime) >= seconds * 1e6; },
              seconds * 4 + 5);
        return states;
    }
};

int64_t counter(const daemon_status_t& s, const std::string& name)
{
    for (int i = 0; i < s.ncounters; ++i)
        if (s.counter_names[static_cast<std::size_t>(i)] == name) return s.counter_values[static_cast<std::size_t>(i)];
    return -1;
}

std::pair<double, double> angle_range(const std::vector<servo_state_t>& v)
{
    double lo = 1e9, hi = -1e9;
    for (const auto& s : v) {
        lo = std::min(lo, s.angle);
        hi = std::max(hi, s.angle);
    }
    return {lo, hi};
}

}  // namespace

// REQUIRE that, on failure, shows both processes' logs as they are at that moment.
#define REQUIRE_LOGGED(cond)                                                                      \
    do {                                                                                          \
        if (!(cond)) FAIL(#cond << "\nugv-servo stderr:\n" << servo.err() << "\nugv-sim stderr:\n" << sim.err()); \
    } while (0)

TEST_CASE("ugv-servo enables the emulated drive, nods, recovers from a fault and shuts down cleanly")
{
    test::TempDir dir;
    const std::string pty = dir / "servo.pty";
    const std::string url = test::lcm_url(7850);
    test::Process sim({test::bin("ugv-sim"), "servo", "--pty", pty, "--node-id", "3"}, dir / "sim.out",
                      dir / "sim.err");
    REQUIRE(test::wait_until([&] { return std::filesystem::exists(pty); }, 10.0));
    test::write_file(dir / "servo.toml",
                     "transport = \"slcan:" + pty + "@115200\"\n"
                     "bitrate = 500000\nnode_id = 3\nmin_tilt_deg = -10.0\nmax_tilt_deg = 40.0\n"
                     // Generous heartbeat and SDO timeouts: a loaded CI machine can stall a
                     // process for a few hundred ms, and this case is not about those.
                     "heartbeat_ms = 300\nsdo_timeout_ms = 500\n"
                     "[profile]\nkind = \"CONSTANT_RATE\"\nnod_min_deg = 0.0\nnod_max_deg = 20.0\n"
                     "rate_deg_s = 40.0\n");
    Watch watch(url);
    test::Process servo({test::bin("ugv-servo"), "--config", dir / "servo.toml", "--lcm-url", url},
                        dir / "servo.out", dir / "servo.err");

    REQUIRE_LOGGED(watch.until([&] {
        return !watch.states.empty() &&
               watch.states.back().cia402_state == servo_state_t::STATE_OPERATION_ENABLED;
    }, 20.0));

    // It nods: over two seconds (two full nods) the angle sweeps the commanded range.
    auto nod = watch.collect(2.0);
    REQUIRE(nod.size() >= 100);  // >= 50 Hz even on a loaded machine (the drive sends 100 Hz)
    auto [lo, hi] = angle_range(nod);
    CHECK(lo < 4 * kDeg);
    CHECK(hi > 16 * kDeg);
    CHECK(lo > -2 * kDeg);
    CHECK(hi < 22 * kDeg);
    for (std::size_t i = 1; i < nod.size(); ++i) REQUIRE(nod[i].seq == nod[i - 1].seq + 1);
    CHECK(nod.back().profile == servo_command_t::PROFILE_CONSTANT_RATE);

    // A fault mid-nod (EMCY 0x8611): seen, reset, operation enabled again, and the nod resumes.
    sim.signal(SIGUSR1);
    REQUIRE_LOGGED(watch.until([&] { return !watch.states.empty() && watch.states.back().fault; }, 5.0));
    CHECK(watch.states.back().fault_code == 0x8611);
    REQUIRE_LOGGED(watch.until([&] {
        return watch.states.back().cia402_state == servo_state_t::STATE_OPERATION_ENABLED;
    }, 10.0));
    nod = watch.collect(2.5);
    std::tie(lo, hi) = angle_range(nod);
    CHECK(hi - lo > 8 * kDeg);  // moving again (the full sweep is checked above; a starved
                                // machine slows the set-point handshake down)

    // The status counters report the fault and its reset.
    watch.status.clear();
    REQUIRE_LOGGED(watch.until([&] { return !watch.status.empty(); }, 5.0));
    const auto& st = watch.status.back();
    CHECK(st.state == daemon_status_t::STATE_RUNNING);
    CHECK(counter(st, "faults") == 1);
    CHECK(counter(st, "fault_resets") >= 1);
    CHECK(counter(st, "emcy") >= 2);
    CHECK(counter(st, "sdo_timeouts") == 0);
    CHECK(counter(st, "heartbeat_losses") == 0);
    CHECK(counter(st, "bus_errors") == 0);

    // SERVO_COMMAND: a HOLD beyond the 40 deg limit is refused and the nod runs on; a HOLD at
    // 10 deg is taken.
    servo_command_t cmd{};
    cmd.profile = servo_command_t::PROFILE_HOLD;
    cmd.hold_angle = 45 * kDeg;
    bus::publish(*watch.bus, "SERVO_COMMAND", cmd);
    cmd.hold_angle = 10 * kDeg;
    bus::publish(*watch.bus, "SERVO_COMMAND", cmd);
    REQUIRE_LOGGED(watch.until([&] {
        return watch.states.back().profile == servo_command_t::PROFILE_HOLD &&
               std::fabs(watch.states.back().angle - 10 * kDeg) < 0.2 * kDeg;
    }, 10.0));
    watch.status.clear();
    REQUIRE_LOGGED(watch.until([&] { return !watch.status.empty(); }, 5.0));
    CHECK(counter(watch.status.back(), "commands_refused") == 1);
    CHECK(counter(watch.status.back(), "commands_accepted") == 1);

    // SIGTERM: halt, disable, exit 0.
    servo.signal(SIGTERM);
    CHECK(servo.wait_exit(5.0) == 0);
    CHECK(servo.err().find("drive halted and disabled") != std::string::npos);
    CHECK(servo.err().find("SERVO_COMMAND refused: hold angle 45") != std::string::npos);
}

TEST_CASE("ugv-servo recovers from a heartbeat loss and from bus-off, reporting DEGRADED meanwhile")
{
    test::TempDir dir;
    const std::string pty = dir / "servo.pty";
    const std::string url = test::lcm_url(7851);
    test::Process sim({test::bin("ugv-sim"), "servo", "--pty", pty, "--node-id", "7", "--loss-duration", "2.5"},
                      dir / "sim.out", dir / "sim.err");
    REQUIRE(test::wait_until([&] { return std::filesystem::exists(pty); }, 10.0));
    test::write_file(dir / "servo.toml", "transport = \"slcan:" + pty + "\"\nnode_id = 7\n[profile]\nkind = \"HOLD\"\nhold_deg = 5.0\n");
    Watch watch(url);
    test::Process servo({test::bin("ugv-servo"), "--config", dir / "servo.toml", "--lcm-url", url},
                        dir / "servo.out", dir / "servo.err");
    REQUIRE_LOGGED(watch.until([&] {
        return !watch.states.empty() && watch.states.back().cia402_state == servo_state_t::STATE_OPERATION_ENABLED;
    }, 20.0));
    // It holds 5 degrees.
    REQUIRE_LOGGED(watch.until([&] { return std::fabs(watch.states.back().angle - 5 * kDeg) < 0.2 * kDeg; }, 10.0));

    sim.signal(SIGUSR2);  // the node drops off the bus for 2.5 s
    watch.status.clear();
    REQUIRE_LOGGED(watch.until([&] {
        return !watch.status.empty() && watch.status.back().state == daemon_status_t::STATE_DEGRADED;
    }, 5.0));
    CHECK(counter(watch.status.back(), "heartbeat_losses") == 1);
    // Back on the bus: configured and enabled again, holding the same angle.
    watch.status.clear();
    REQUIRE_LOGGED(watch.until([&] {
        return !watch.status.empty() && watch.status.back().state == daemon_status_t::STATE_RUNNING;
    }, 15.0));
    CHECK(counter(watch.status.back(), "reinits") >= 1);
    watch.states.clear();
    REQUIRE_LOGGED(watch.until([&] { return watch.states.size() > 10; }, 5.0));
    CHECK(watch.states.back().angle == Approx(5 * kDeg).margin(0.3 * kDeg));

    // The adapter's controller goes bus-off: counted, the interface closed and reopened, the
    // drive configured again.
    sim.signal(SIGHUP);
    watch.status.clear();
    REQUIRE_LOGGED(watch.until([&] {
        return !watch.status.empty() && counter(watch.status.back(), "bus_errors") == 1 &&
               counter(watch.status.back(), "reconnects") == 1 &&
               watch.status.back().state == daemon_status_t::STATE_RUNNING;
    }, 15.0));
    watch.states.clear();
    REQUIRE_LOGGED(watch.until([&] {
        return watch.states.size() > 10 &&
               watch.states.back().cia402_state == servo_state_t::STATE_OPERATION_ENABLED;
    }, 5.0));
    servo.signal(SIGTERM);
    CHECK(servo.wait_exit(5.0) == 0);
}

TEST_CASE("ugv-servo rejects a bad configuration with one line and exit status 2")
{
    test::TempDir dir;
    test::write_file(dir / "bad.toml", "transport = \"slcan:/dev/null\"\n[profile]\nkind = \"HOLD\"\nhold_deg = 60.0\n");
    const int rc = test::run({test::bin("ugv-servo"), "--config", dir / "bad.toml"}, dir / "out", dir / "err", 20.0);
    CHECK(rc == 2);
    const std::string err = test::read_file(dir / "err");
    CHECK(err.find("profile.kind") != std::string::npos);
    CHECK(err.find("outside the tilt limits") != std::string::npos);
    test::write_file(dir / "bad2.toml", "transport = \"carrier-pigeon:0\"\n");
    CHECK(test::run({test::bin("ugv-servo"), "--config", dir / "bad2.toml"}, dir / "out", dir / "err", 20.0) == 2);
    CHECK(test::read_file(dir / "err").find("transport") != std::string::npos);
}
