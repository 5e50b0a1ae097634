// ugv-servo against its drive emulator (ugv-sim servo over slcan on a pty): SERVO_COMMANDs
// with an unknown profile, a rate that is not finite, too small or too large, or a spacing
// and height that would stop the nod are refused and counted, the nod runs on; a flood of
// 5,000 refused commands is counted one by one and logged in a bounded number of lines.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <functional>
#include <limits>
#include <memory>
#include <numbers>
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
        bus::subscribe<servo_state_t>(*bus, "SERVO_STATE",
                                      [this](const std::string&, const servo_state_t& m, int64_t) { states.push_back(m); });
        bus::subscribe<daemon_status_t>(*bus, "STATUS_SERVO",
                                        [this](const std::string&, const daemon_status_t& m, int64_t) { status.push_back(m); });
    }
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
    // The states of the next `seconds` of the servo's own time stamps.
    std::vector<servo_state_t> collect(double seconds)
    {
        states.clear();
        until([&] { return !states.empty() && static_cast<double>(states.back().utime - states.front().utime) >= seconds * 1e6; },
              seconds * 4 + 5);
        return states;
    }
    // A status message published after every message sent so far was handled: the first
    // one that is two statuses after now.
    daemon_status_t fresh_status()
    {
        status.clear();
        until([&] { return status.size() >= 2; }, 10.0);
        return status.empty() ? daemon_status_t{} : status.back();
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

std::size_t count_of(const std::string& text, const std::string& what)
{
    std::size_t n = 0;
    for (auto p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
    return n;
}

servo_command_t nod(double min_deg, double max_deg, double rate_rad_s)
{
    servo_command_t c{};
    c.profile = servo_command_t::PROFILE_CONSTANT_RATE;
    c.min_tilt = min_deg * kDeg;
    c.max_tilt = max_deg * kDeg;
    c.rate = rate_rad_s;
    return c;
}

}  // namespace

#define REQUIRE_LOGGED(cond)                                                                                      \
    do {                                                                                                          \
        if (!(cond)) FAIL(#cond << "\nugv-servo stderr:\n" << servo.err() << "\nugv-sim stderr:\n" << sim.err()); \
    } while (0)

TEST_CASE("ugv-servo refuses bad SERVO_COMMANDs, counted, logged with a rate limit, and the nod runs on")
{
    test::TempDir dir;
    const std::string pty = dir / "servo.pty";
    const std::string url = test::lcm_url(7731);
    test::Process sim({test::bin("ugv-sim"), "servo", "--pty", pty, "--node-id", "3"}, dir / "sim.out", dir / "sim.err");
    REQUIRE(test::wait_until([&] { return std::filesystem::exists(pty); }, 10.0));
    test::write_file(dir / "servo.toml",
                     "transport = \"slcan:" + pty + "@115200\"\n"
                     "node_id = 3\nmin_tilt_deg = -10.0\nmax_tilt_deg = 40.0\n"
                     "heartbeat_ms = 300\nsdo_timeout_ms = 500\n"  // a loaded machine stalls processes
                     "[profile]\nkind = \"CONSTANT_RATE\"\nnod_min_deg = 0.0\nnod_max_deg = 20.0\nrate_deg_s = 40.0\n");
    Watch watch(url);
    test::Process servo({test::bin("ugv-servo"), "--config", dir / "servo.toml", "--lcm-url", url}, dir / "servo.out",
                        dir / "servo.err");
    REQUIRE_LOGGED(watch.until(
        [&] { return !watch.states.empty() && watch.states.back().cia402_state == servo_state_t::STATE_OPERATION_ENABLED; },
        20.0));

    // One of each bad kind.
    std::vector<servo_command_t> bad;
    servo_command_t c = nod(0, 20, 40 * kDeg);
    c.profile = 99;
    bad.push_back(c);
    c.profile = -1;
    bad.push_back(c);
    bad.push_back(nod(0, 20, 1e-300));                                      // a nod of 1e300 s
    bad.push_back(nod(0, 20, 0.001 * kDeg));                                // a nod of 11 hours
    bad.push_back(nod(0, 20, std::numeric_limits<double>::quiet_NaN()));
    bad.push_back(nod(0, 20, std::numeric_limits<double>::infinity()));
    bad.push_back(nod(0, 20, 1e300));                                       // beyond max_rate_deg_s
    bad.push_back(nod(0, 20, -1.0));
    c = nod(2, 30, 0);
    c.profile = servo_command_t::PROFILE_UNIFORM_GROUND_SPACING;
    c.ground_spacing = 1e-9;
    c.sensor_height = 1e9;
    bad.push_back(c);
    c.ground_spacing = 0.2;  // a sane spacing, but 1000 km up: a nod of years
    c.sensor_height = 1e6;
    bad.push_back(c);
    c.sensor_height = std::numeric_limits<double>::quiet_NaN();
    bad.push_back(c);
    c = nod(0, 20, 0);
    c.profile = servo_command_t::PROFILE_HOLD;
    c.hold_angle = std::numeric_limits<double>::infinity();
    bad.push_back(c);
    for (const auto& b : bad) REQUIRE(bus::publish(*watch.bus, "SERVO_COMMAND", b));
    const auto bad_sent = std::chrono::steady_clock::now();

    // The nod runs on as configured: two full nods' worth of the 0-20 deg sweep.
    const auto after = watch.collect(2.0);
    REQUIRE(after.size() >= 100);
    const auto [lo, hi] = angle_range(after);
    CHECK(lo < 4 * kDeg);
    CHECK(hi > 16 * kDeg);
    CHECK(after.back().profile == servo_command_t::PROFILE_CONSTANT_RATE);
    daemon_status_t st = watch.fresh_status();
    CHECK(st.state == daemon_status_t::STATE_RUNNING);
    CHECK(counter(st, "commands_refused") == static_cast<int64_t>(bad.size()));
    CHECK(counter(st, "commands_accepted") == 0);
    const std::string log = servo.err();
    CHECK(log.find("SERVO_COMMAND refused: unknown profile 99") != std::string::npos);

    // A good command is still taken after all that.
    REQUIRE(bus::publish(*watch.bus, "SERVO_COMMAND", nod(5, 10, 20 * kDeg)));
    REQUIRE_LOGGED(watch.until(
        [&] {
            const auto r = angle_range(watch.collect(1.0));
            return r.first > 4 * kDeg && r.second < 11 * kDeg && r.second - r.first > 3 * kDeg;
        },
        15.0));
    st = watch.fresh_status();
    CHECK(counter(st, "commands_accepted") == 1);

    // The flood: 5,000 refused commands, paced at ~10,000 a second (what a socket buffer
    // takes). Each is counted; the log gains one line per 5 s interval, not one per command.
    // Past the log's 5 s interval since the bad commands: the flood's first refusal logs a
    // line, with the count of the bad ones that were not logged.
    std::this_thread::sleep_until(bad_sent + std::chrono::milliseconds(5500));
    const std::size_t lines_before = count_of(servo.err(), "SERVO_COMMAND refused");
    const auto t0 = std::chrono::steady_clock::now();
    const servo_command_t flood_cmd = nod(0, 20, 1e-300);
    for (int k = 0; k < 5000; ++k) {
        bus::publish(*watch.bus, "SERVO_COMMAND", flood_cmd);
        if (k % 50 == 49) std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    const double flood_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const daemon_status_t before_stable = watch.fresh_status();
    st = watch.fresh_status();  // no change between two fresh statuses: every command handled
    const int64_t refused = counter(st, "commands_refused") - static_cast<int64_t>(bad.size());
    INFO("flood of 5000 over " << flood_s << " s; refused " << refused);
    CHECK(counter(before_stable, "commands_refused") == counter(st, "commands_refused"));
    // Everything the bus dispatched was a command, and each was either accepted or refused:
    // none was lost between the bus and the counter (a loaded machine may drop datagrams in
    // the kernel, which the bus cannot see).
    CHECK(counter(st, "commands_refused") + counter(st, "commands_accepted") == counter(st, "bus_received"));
    CHECK(refused >= 2500);
    CHECK(refused <= 5000);
    const std::size_t lines = count_of(servo.err(), "SERVO_COMMAND refused") - lines_before;
    // The first refusal of the flood may log (the last was > 5 s ago), then at most one line
    // per 5 s of flood and of the two status periods after it.
    CHECK(lines >= 1);
    CHECK(lines <= 2 + static_cast<std::size_t>(flood_s / 5.0) + 1);
    CHECK(servo.err().find("(repeated " + std::to_string(bad.size() - 1) + " times") != std::string::npos);
    // And the nod still runs (the command above: 5-10 deg).
    const auto r = angle_range(watch.collect(1.5));
    CHECK(r.first < 6.5 * kDeg);
    CHECK(r.second > 8.5 * kDeg);

    servo.signal(SIGTERM);
    CHECK(servo.wait_exit(5.0) == 0);
}
