// ugv-servo drives the emulated CiA 402 drive (ugv-sim servo) through slcan on a pty: it
// reaches Operation Enabled and nods; a fault raised mid-nod is reset and the nod resumes;
// the counters say so; SIGTERM halts, disables and exits 0. Then the line faults of issue 11:
// bit errors, cut lines, garbage, BEL refusals and a bus at another bitrate.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <numbers>
#include <sstream>
#include <thread>
#include <vector>

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

// Voluntary context switches of every thread of a process: how often it went to sleep.
int64_t voluntary_switches(pid_t pid)
{
    int64_t total = 0;
    for (const auto& task : std::filesystem::directory_iterator("/proc/" + std::to_string(pid) + "/task")) {
        std::ifstream in(task.path() / "status");
        std::string line;
        while (std::getline(in, line))
            if (line.rfind("voluntary_ctxt_switches:", 0) == 0) total += std::stoll(line.substr(24));
    }
    return total;
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
    const int64_t switches_before = voluntary_switches(servo.pid());
    const auto wall_before = std::chrono::steady_clock::now();
    auto nod = watch.collect(2.0);
    // Once the drive runs, the control tick (100 Hz) reads the bus and the daemon wakes for
    // frames only in a 50 ms window every 0.5 s: ~120 wake-ups/s, where waking for each
    // TPDO1, TPDO2 and heartbeat line besides the tick made ~280 (docs/servo.md).
    const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_before).count();
    const double wakeups_per_s = static_cast<double>(voluntary_switches(servo.pid()) - switches_before) / wall_s;
    INFO("ugv-servo wake-ups: " << wakeups_per_s << " per second");
    CHECK(wakeups_per_s < 200);
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
    const auto node_back = std::chrono::steady_clock::now() + std::chrono::milliseconds(2500);
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
    std::printf("servo heartbeat back (node off the bus 2.5 s): RUNNING reported %.2f s after the node returned\n",
                std::chrono::duration<double>(std::chrono::steady_clock::now() - node_back).count());
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

// Device faults on the slcan line (issue 11). The adapter's ASCII lines carry no checksum, so
// the daemon must drop malformed lines (rx_errors) without restarting the interface, and its
// TPDO plausibility check (state confirmed by two TPDOs, position within what the axis can
// move) keeps a bit error that leaves a well-formed but wrong frame off SERVO_STATE.
namespace {

// The nod every fault case runs: 0-20 deg at 40 deg/s, the velocity cap at 60 deg/s (so the
// plausibility bound is 2 x 60 deg/s x 10 ms + 0.5 deg = 1.7 deg per TPDO period).
const char* kFaultCaseConfig =
    "bitrate = 500000\nnode_id = 3\nmin_tilt_deg = -10.0\nmax_tilt_deg = 40.0\nmax_rate_deg_s = 60.0\n"
    "heartbeat_ms = 300\nsdo_timeout_ms = 500\n"
    "[profile]\nkind = \"CONSTANT_RATE\"\nnod_min_deg = 0.0\nnod_max_deg = 20.0\nrate_deg_s = 40.0\n";

struct FaultRun
{
    test::TempDir dir;
    std::string pty = dir / "servo.pty";
    std::unique_ptr<test::Process> sim;
    std::unique_ptr<Watch> watch;
    std::unique_ptr<test::Process> servo;

    FaultRun(int port, const std::vector<std::string>& sim_faults)
    {
        start_sim(sim_faults);
        test::write_file(dir / "servo.toml", "transport = \"slcan:" + pty + "\"\n" + kFaultCaseConfig);
        const std::string url = test::lcm_url(port);
        watch = std::make_unique<Watch>(url);
        servo = std::make_unique<test::Process>(
            std::vector<std::string>{test::bin("ugv-servo"), "--config", dir / "servo.toml", "--lcm-url", url},
            dir / "servo.out", dir / "servo.err");
    }
    // A new emulator (the adapter unplugged and another one plugged in).
    void start_sim(const std::vector<std::string>& faults)
    {
        if (sim) {
            sim->signal(SIGKILL);
            sim->wait_exit(5.0);
        }
        std::vector<std::string> args{test::bin("ugv-sim"), "servo", "--pty", pty, "--node-id", "3"};
        args.insert(args.end(), faults.begin(), faults.end());
        sim = std::make_unique<test::Process>(args, dir / "sim.out", dir / "sim.err");
        REQUIRE(test::wait_until([&] { return std::filesystem::exists(pty); }, 10.0));
    }
    std::string logs() const { return "\nugv-servo stderr:\n" + servo->err() + "\nugv-sim stderr:\n" + sim->err(); }
    bool operation_enabled()
    {
        return !watch->states.empty() && watch->states.back().cia402_state == servo_state_t::STATE_OPERATION_ENABLED;
    }
    // Waits up to 20 s for a DEGRADED status whose last_error contains `text`.
    bool degraded_saying(const std::string& text)
    {
        return watch->until([&] { return !watch->status.empty() && watch->status.back().state == daemon_status_t::STATE_DEGRADED &&
                                         watch->status.back().last_error.find(text) != std::string::npos; },
                            20.0);
    }
};

// Every published angle inside the nod (0-20 deg, with the position loop's overshoot) and no
// step between two published samples larger than the axis can move: no corrupted position.
void check_nod_is_clean(const std::vector<servo_state_t>& states)
{
    int outside = 0, jumps = 0;
    for (std::size_t i = 0; i < states.size(); ++i) {
        if (states[i].angle < -2 * kDeg || states[i].angle > 22 * kDeg) ++outside;
        if (i == 0) continue;
        const double dt = std::max(static_cast<double>(states[i].utime - states[i - 1].utime) * 1e-6, 0.01);
        if (std::fabs(states[i].angle - states[i - 1].angle) > 2 * 60 * kDeg * dt + 0.5 * kDeg) ++jumps;
        CHECK(states[i].seq == states[i - 1].seq + 1);
    }
    CHECK(outside == 0);
    CHECK(jumps == 0);
    const auto [lo, hi] = angle_range(states);
    CHECK(hi - lo > 8 * kDeg);  // still nodding
    for (const auto& s : states) {
        CHECK(!s.fault);
        if (s.fault) break;
    }
}

void run_with_line_faults(int port, const std::vector<std::string>& faults, const char* what)
{
    FaultRun run(port, faults);
    if (!run.watch->until([&] { return run.operation_enabled(); }, 40.0)) FAIL("never enabled" << run.logs());
    const auto nod = run.watch->collect(4.0);
    REQUIRE(nod.size() >= 200);
    check_nod_is_clean(nod);
    run.watch->status.clear();
    if (!run.watch->until([&] { return !run.watch->status.empty() &&
                                       run.watch->status.back().state == daemon_status_t::STATE_RUNNING; }, 20.0))
        FAIL("not RUNNING" << run.logs());
    const daemon_status_t st = run.watch->status.back();
    CHECK(counter(st, "rx_errors") > 0);
    CHECK(counter(st, "faults") == 0);
    CHECK(counter(st, "bus_errors") == 0);
    std::printf("servo %s: %zu states in 4 s, rx_errors %lld, tpdo_implausible %lld, reinits %lld, sdo_timeouts %lld, "
                "reconnects %lld\n",
                what, nod.size(), static_cast<long long>(counter(st, "rx_errors")),
                static_cast<long long>(counter(st, "tpdo_implausible")), static_cast<long long>(counter(st, "reinits")),
                static_cast<long long>(counter(st, "sdo_timeouts")), static_cast<long long>(counter(st, "reconnects")));
    run.servo->signal(SIGTERM);
    CHECK(run.servo->wait_exit(5.0) == 0);
}

}  // namespace

TEST_CASE("ugv-servo with bit errors at 1e-3 per byte on the slcan line: nothing corrupt published, nods on")
{
    run_with_line_faults(7852, {"--bit-error-rate", "0.001", "--seed", "5"}, "bit errors 1e-3");
}

TEST_CASE("ugv-servo with bit errors at 1e-2 per byte on the slcan line: nothing corrupt published, nods on")
{
    run_with_line_faults(7853, {"--bit-error-rate", "0.01", "--seed", "5"}, "bit errors 1e-2");
}

TEST_CASE("ugv-servo with slcan lines cut short before their CR: dropped and counted, nods on")
{
    run_with_line_faults(7854, {"--truncate-every", "25", "--seed", "6"}, "every 25th frame line truncated");
}

TEST_CASE("ugv-servo with garbage bytes between slcan lines: dropped and counted, nods on")
{
    run_with_line_faults(7855, {"--garbage-every", "0.2", "--garbage-bytes", "24", "--seed", "7"},
                         "24 garbage bytes every 0.2 s");
}

TEST_CASE("ugv-servo when the adapter refuses transmits with BEL: counted, logged, the interface restarted, nods on")
{
    FaultRun run(7856, {"--refuse-tx-every", "400"});
    if (!run.watch->until([&] { return run.operation_enabled(); }, 20.0)) FAIL("never enabled" << run.logs());
    run.watch->states.clear();
    // At ~100 transmits a second, a refusal every few seconds: each one is a restart of the
    // interface (C, S6, O) and of the drive session.
    if (!run.watch->until([&] { return !run.watch->status.empty() && counter(run.watch->status.back(), "reconnects") >= 1 &&
                                       counter(run.watch->status.back(), "bus_errors") >= 1 &&
                                       run.watch->status.back().state == daemon_status_t::STATE_RUNNING; }, 30.0))
        FAIL("no BEL counted, or not back" << run.logs());
    const std::size_t before = run.watch->states.size();
    if (!run.watch->until([&] { return run.watch->states.size() > before + 200; }, 10.0)) FAIL("no nod" << run.logs());
    // The outage: the longest gap between two SERVO_STATEs.
    const auto& states = run.watch->states;
    int64_t gap_us = 0;
    for (std::size_t i = 1; i < states.size(); ++i) gap_us = std::max(gap_us, states[i].utime - states[i - 1].utime);
    std::printf("servo BEL to a transmit: SERVO_STATE interrupted for %.2f s at most (restart of the interface)\n",
                static_cast<double>(gap_us) * 1e-6);
    const std::vector<servo_state_t> last(states.end() - 200, states.end());
    const auto [lo, hi] = angle_range(last);
    CHECK(hi - lo > 8 * kDeg);
    CHECK(run.servo->err().find("bus error: adapter error (BEL)") != std::string::npos);
    run.servo->signal(SIGTERM);
    CHECK(run.servo->wait_exit(5.0) == 0);
}

TEST_CASE("ugv-servo on a bus at another bitrate: DEGRADED naming the bitrate, nothing published, back when it matches")
{
    FaultRun run(7857, {"--bus-bitrate", "250000"});
    if (!run.degraded_saying("at 500000 bit/s")) FAIL("no DEGRADED naming the bitrate" << run.logs());
    const std::string why = run.watch->status.back().last_error;
    INFO(why);
    CHECK(why.find("nothing received from the bus") != std::string::npos);
    CHECK(why.find("node_id 3") != std::string::npos);
    CHECK(run.watch->states.empty());
    CHECK(run.servo->running());
    CHECK(run.servo->err().find("nothing received from the bus at 500000 bit/s") != std::string::npos);

    // The bus set to 500 kbit/s (another adapter plugged in): the daemon reopens and enables.
    run.start_sim({});
    const auto back = std::chrono::steady_clock::now();
    if (!run.watch->until([&] { return run.operation_enabled(); }, 20.0)) FAIL("never enabled" << run.logs());
    const double enabled_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - back).count();
    if (!run.watch->until([&] { return !run.watch->status.empty() &&
                                       run.watch->status.back().state == daemon_status_t::STATE_RUNNING; }, 20.0))
        FAIL("not RUNNING" << run.logs());
    std::printf("servo bitrate fixed: Operation Enabled %.2f s after the adapter came back, RUNNING reported %.2f s\n",
                enabled_s, std::chrono::duration<double>(std::chrono::steady_clock::now() - back).count());
    run.servo->signal(SIGTERM);
    CHECK(run.servo->wait_exit(5.0) == 0);
}

TEST_CASE("ugv-servo with the adapter's serial side at another rate: DEGRADED naming the rate, nothing published, back when it matches")
{
    // The adapter at 57600, the daemon at 115200: neither understands the other.
    FaultRun run(7858, {"--serial-baud", "57600"});
    if (!run.degraded_saying("not at 115200 baud")) FAIL("no DEGRADED naming the serial rate" << run.logs());
    CHECK(run.watch->states.empty());
    CHECK(run.servo->running());

    // The adapter at 115200 (the right one plugged in): the daemon reopens and enables.
    run.start_sim({});
    if (!run.watch->until([&] { return run.operation_enabled(); }, 20.0)) FAIL("never enabled" << run.logs());
    run.servo->signal(SIGTERM);
    CHECK(run.servo->wait_exit(5.0) == 0);
}

// Drives as they really are (issue 25): fewer PDOs, fixed mappings, an object limit per PDO,
// no heartbeat producer, SYNC-only TPDOs. For each shape ugv-servo must reach Operation
// Enabled and nod with SERVO_STATE at the drive's TPDO rate (100 Hz), the plan's degradations
// flagged in STATUS_SERVO. One emulator + daemon pair per shape, a few seconds each.
namespace {

struct Shape
{
    const char* name;
    std::vector<std::string> sim_args;
    std::vector<std::string> flags;  // degraded_* counters that must be 1 (the others 0)
};

const char* kShapeFlags[] = {"degraded_fixed_mapping",       "degraded_split_status",      "degraded_velocity_derived",
                             "degraded_profile_velocity_sdo", "degraded_setpoint_sdo",      "degraded_supervised_by_tpdo",
                             "degraded_sync_only",            "degraded_no_acceleration"};

}  // namespace

TEST_CASE("ugv-servo reaches Operation Enabled and nods at 100 Hz with every drive shape", "[shapes]")
{
    const std::vector<Shape> shapes = {
        {"every resource", {}, {}},
        {"one TPDO, one RPDO", {"--tpdos", "1", "--rpdos", "1"}, {"degraded_velocity_derived", "degraded_profile_velocity_sdo"}},
        {"fixed mappings", {"--fixed-mapping"}, {"degraded_fixed_mapping"}},
        {"one fixed TPDO and RPDO", {"--tpdos", "1", "--rpdos", "1", "--fixed-mapping"},
         {"degraded_fixed_mapping", "degraded_velocity_derived", "degraded_profile_velocity_sdo"}},
        {"one object per PDO", {"--max-mapped", "1"}, {"degraded_split_status"}},
        {"one object per PDO, two RPDOs", {"--max-mapped", "1", "--rpdos", "2"},
         {"degraded_split_status", "degraded_profile_velocity_sdo"}},
        {"one object per PDO, one RPDO", {"--max-mapped", "1", "--rpdos", "1"},
         {"degraded_split_status", "degraded_profile_velocity_sdo", "degraded_setpoint_sdo"}},
        {"no heartbeat producer", {"--no-heartbeat"}, {"degraded_supervised_by_tpdo"}},
        {"SYNC-only TPDOs", {"--sync-only"}, {"degraded_sync_only"}},
        {"one SYNC-only TPDO, one RPDO, no heartbeat, two objects per PDO",
         {"--tpdos", "1", "--rpdos", "1", "--sync-only", "--no-heartbeat", "--max-mapped", "2"},
         {"degraded_velocity_derived", "degraded_profile_velocity_sdo", "degraded_supervised_by_tpdo", "degraded_sync_only"}},
        {"no acceleration objects", {"--remove-object", "0x6083", "--remove-object", "0x6084"}, {"degraded_no_acceleration"}},
    };
    int port = 7825;
    for (const auto& shape : shapes) {
        INFO("shape: " << shape.name);
        FaultRun run(port++, shape.sim_args);
        if (!run.watch->until([&] { return run.operation_enabled(); }, 20.0)) FAIL("never enabled" << run.logs());
        const auto nod = run.watch->collect(1.5);
        const double span_s = static_cast<double>(nod.back().utime - nod.front().utime) * 1e-6;
        const double rate_hz = static_cast<double>(nod.size() - 1) / span_s;
        const auto [lo, hi] = angle_range(nod);
        std::printf("servo shape %-66s %4zu states, %.1f Hz over %.2f s, nod %.1f..%.1f deg\n", shape.name, nod.size(),
                    rate_hz, span_s, lo / kDeg, hi / kDeg);
        // Event timer: stamped on the drive's 10 ms cadence (100.0 Hz). SYNC: one per control
        // tick of the daemon, stamped on arrival (97-99 Hz measured; a late tick skips one).
        const bool sync = std::find(shape.sim_args.begin(), shape.sim_args.end(), "--sync-only") != shape.sim_args.end();
        CHECK(rate_hz > (sync ? 90.0 : 95.0));
        CHECK(rate_hz < 105.0);
        CHECK(hi - lo > 5 * kDeg);  // nodding (1.5 s of a 0-20 deg nod at 40 deg/s)
        for (std::size_t i = 1; i < nod.size(); ++i) REQUIRE(nod[i].seq == nod[i - 1].seq + 1);
        run.watch->status.clear();
        if (!run.watch->until([&] { return !run.watch->status.empty() &&
                                           run.watch->status.back().state == daemon_status_t::STATE_RUNNING; }, 10.0))
            FAIL("not RUNNING" << run.logs());
        const daemon_status_t st = run.watch->status.back();
        for (const char* flag : kShapeFlags) {
            const bool expected = std::find(shape.flags.begin(), shape.flags.end(), flag) != shape.flags.end();
            INFO(flag);
            CHECK(counter(st, flag) == (expected ? 1 : 0));
        }
        CHECK(counter(st, "reinits") == 0);
        CHECK(counter(st, "mandatory_missing") == 0);
        // Each degradation is one log line (said once, however often the session restarts).
        std::vector<std::string> lines;
        std::istringstream err(run.servo->err());
        for (std::string line; std::getline(err, line);) {
            const auto at = line.find("degraded: ");
            if (at != std::string::npos) lines.push_back(line.substr(at));
        }
        CHECK(lines.empty() == shape.flags.empty());
        std::sort(lines.begin(), lines.end());
        CHECK(std::adjacent_find(lines.begin(), lines.end()) == lines.end());
        run.servo->signal(SIGTERM);
        CHECK(run.servo->wait_exit(5.0) == 0);
    }
}

TEST_CASE("ugv-servo with a drive that lacks a mandatory object: says which once, DEGRADED, retries with back-off",
          "[shapes]")
{
    FaultRun run(7836, {"--remove-object", "0x607A"});
    if (!run.degraded_saying("target position 0x607A")) FAIL("no DEGRADED naming 0x607A" << run.logs());
    std::this_thread::sleep_for(std::chrono::seconds(3));
    run.watch->status.clear();
    if (!run.watch->until([&] { return !run.watch->status.empty(); }, 5.0)) FAIL("no status" << run.logs());
    const daemon_status_t st = run.watch->status.back();
    CHECK(st.state == daemon_status_t::STATE_DEGRADED);
    CHECK(counter(st, "mandatory_missing") == 1);
    // Retried with back-off (0.1 s doubling to 1 s), not spinning: a handful in ~4 s.
    CHECK(counter(st, "reinits") >= 2);
    CHECK(counter(st, "reinits") <= 10);
    CHECK(run.watch->states.empty());
    const std::string err = run.servo->err();
    std::size_t said = 0;
    for (auto at = err.find("lacks mandatory"); at != std::string::npos; at = err.find("lacks mandatory", at + 1)) ++said;
    INFO(err);
    CHECK(said == 2);  // the session's error and the re-initialisation, once each
    run.servo->signal(SIGTERM);
    CHECK(run.servo->wait_exit(5.0) == 0);
}

TEST_CASE("ugv-servo --probe prints identity, PDO resources and the plan; exits 1 naming the node when none answers",
          "[shapes]")
{
    FaultRun run(7837, {"--tpdos", "1", "--rpdos", "1", "--fixed-mapping"});
    run.servo->signal(SIGTERM);
    run.servo->wait_exit(5.0);
    test::write_file(run.dir / "probe.toml", "transport = \"slcan:" + run.pty + "\"\nnode_id = 3\n");
    const int rc = test::run({test::bin("ugv-servo"), "--config", run.dir / "probe.toml", "--probe"}, run.dir / "probe.out",
                             run.dir / "probe.err", 20.0);
    const std::string out = test::read_file(run.dir / "probe.out");
    INFO(out << test::read_file(run.dir / "probe.err"));
    CHECK(rc == 0);
    CHECK(out.find("identity (0x1018): vendor 0x00000ABC") != std::string::npos);
    CHECK(out.find("TPDO1: COB-ID 0x00000183, mapping statusword 0x6041 + position actual 0x6064, fixed (0x06010002") !=
          std::string::npos);
    CHECK(out.find("TPDO2: absent") != std::string::npos);
    CHECK(out.find("profile velocity by SDO when it changes") != std::string::npos);
    CHECK(out.find("velocity derived from position") != std::string::npos);
    // The drive was left alone: pre-operational, never enabled.
    CHECK(run.sim->err().find("raising") == std::string::npos);

    test::write_file(run.dir / "none.toml", "transport = \"slcan:" + run.pty + "\"\nnode_id = 9\nsdo_timeout_ms = 50\n");
    CHECK(test::run({test::bin("ugv-servo"), "--config", run.dir / "none.toml", "--probe"}, run.dir / "none.out",
                    run.dir / "none.err", 20.0) == 1);
    const std::string err = test::read_file(run.dir / "none.err");
    INFO(err);
    CHECK(err.find("no drive answered as node 9") != std::string::npos);
    CHECK(std::count(err.begin(), err.end(), '\n') == 1);
}
