// The daemon plumbing seen from outside, as systemd and an operator see it.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <map>

#include "ugv/bus/typed.hpp"
#include "ugv/daemon_status_t.hpp"
#include "ugv/io/clock.hpp"
#include "ugv/raw_bytes_t.hpp"
#include "ugv_test/notify_socket.hpp"
#include "ugv_test/process.hpp"

using namespace ugv;

namespace {

std::string first_line(const std::string& s) { return s.substr(0, s.find('\n')); }

}  // namespace

TEST_CASE("daemon: READY, WATCHDOG while healthy, status on LCM, and STOPPING with a clean exit on SIGTERM")
{
    test::TempDir dir;
    test::NotifySocket notify(dir / "notify");
    const std::string url = test::lcm_url(7611);
    auto listen = bus::open_live(url);
    std::vector<daemon_status_t> status;
    bus::subscribe<daemon_status_t>(*listen, "STATUS_DAEMON", [&](const std::string&, const daemon_status_t& m, int64_t) {
        status.push_back(m);
    });
    test::Process d({test::bin("ugv-test-daemon"), "--lcm-url", url, "--instance", "bench"}, dir / "out", dir / "err",
                    {notify.env(), "WATCHDOG_USEC=400000"});
    // No WATCHDOG_PID: sd_watchdog_enabled() then accepts the watchdog for any pid.
    REQUIRE(notify.wait_for("READY=1", 10));
    REQUIRE(notify.wait_for("WATCHDOG=1", 5));
    REQUIRE(test::wait_until([&] { listen->handle(20); return status.size() >= 2; }, 10));
    const daemon_status_t& s = status.back();
    CHECK(s.name == "ugv-test-daemon");
    CHECK(s.instance == "bench");
    CHECK(s.pid == d.pid());
    CHECK(s.state == daemon_status_t::STATE_RUNNING);
    REQUIRE(s.ncounters >= 1);
    CHECK(s.counter_names[0] == "ticks");
    CHECK(s.counter_values[0] > 0);
    CHECK(s.seq == status.front().seq + static_cast<int64_t>(status.size()) - 1);

    const int64_t t0 = io::monotonic_us();
    d.signal(SIGTERM);
    CHECK(notify.wait_for("STOPPING=1", 2));
    CHECK(d.wait_exit(2.0) == 0);
    CHECK(io::monotonic_us() - t0 < 1'000'000);
}

TEST_CASE("daemon: no WATCHDOG ping while unhealthy, so systemd would restart it")
{
    test::TempDir dir;
    test::NotifySocket notify(dir / "notify");
    test::write_file(dir / "d.toml", "healthy = false\n");
    test::Process d({test::bin("ugv-test-daemon"), "--config", dir / "d.toml", "--lcm-url", test::lcm_url(7612)},
                    dir / "out", dir / "err", {notify.env(), "WATCHDOG_USEC=200000"});
    REQUIRE(notify.wait_for("READY=1", 10));
    CHECK_FALSE(notify.wait_for("WATCHDOG=1", 1.0));
    d.signal(SIGINT);
    CHECK(d.wait_exit(2.0) == 0);
}

TEST_CASE("daemon: config errors exit 2 with one line FILE: KEY: why")
{
    test::TempDir dir;
    const auto run_with = [&](const std::string& toml) {
        test::write_file(dir / "d.toml", toml);
        const int code = test::run({test::bin("ugv-test-daemon"), "--config", dir / "d.toml"}, dir / "o", dir / "e");
        return std::make_pair(code, test::read_file(dir / "e"));
    };
    auto [code, err] = run_with("period_ms = 0\n");
    CHECK(code == 2);
    CHECK(err == dir / "d.toml" + ": period_ms: 0 is out of range [1, 10000]\n");
    std::tie(code, err) = run_with("chanel = \"X\"\n");
    CHECK(code == 2);
    CHECK(err == dir / "d.toml" + ": chanel: unknown key\n");
    std::tie(code, err) = run_with("bus_batch_ms = 500\n");
    CHECK(code == 2);
    CHECK(err == dir / "d.toml" + ": bus_batch_ms: 500 is out of range [0, 100]\n");
    std::tie(code, err) = run_with("[realtime]\nfifo_priority = 120\n");
    CHECK(code == 2);
    CHECK(err == dir / "d.toml" + ": realtime.fifo_priority: 120 is out of range [0, 99]\n");
    code = test::run({test::bin("ugv-test-daemon"), "--config", dir / "missing.toml"}, dir / "o", dir / "e");
    CHECK(code == 2);
    CHECK(test::read_file(dir / "e") == dir / "missing.toml" + ": -: cannot read the file: No such file or directory\n");
    code = test::run({test::bin("ugv-test-daemon"), "--lcm-url", "bogus://"}, dir / "o", dir / "e");
    CHECK(code == 2);
    CHECK(test::read_file(dir / "e").find("ugv-test-daemon: LCM cannot be created for 'bogus://'") != std::string::npos);
}

TEST_CASE("daemon: --print-config prints the effective config, --version the version")
{
    test::TempDir dir;
    test::write_file(dir / "d.toml", "period_ms = 20\n");
    REQUIRE(test::run({test::bin("ugv-test-daemon"), "--config", dir / "d.toml", "--print-config"}, dir / "o", dir / "e") == 0);
    const std::string out = test::read_file(dir / "o");
    CHECK(out.find("period_ms = 20") != std::string::npos);
    CHECK(out.find("channel = 'TICK'") != std::string::npos);
    CHECK(out.find("status_channel = 'STATUS_DAEMON'") != std::string::npos);
    REQUIRE(test::run({test::bin("ugv-test-daemon"), "--version"}, dir / "o", dir / "e") == 0);
    CHECK(first_line(test::read_file(dir / "o")) == "ugv-test-daemon 0.1.0");
}

TEST_CASE("daemon: --replay LOG --out LOG is deterministic, byte for byte")
{
    test::TempDir dir;
    {
        int64_t t = 1000;
        auto w = bus::open_log_writer(dir / "in.lcm", [&] { return t; });
        for (int k = 0; k < 100; ++k) {
            raw_bytes_t m{};
            m.utime = t;
            m.seq = k;
            m.device = "x";
            m.nbytes = 3;
            m.data = {1, 2, static_cast<uint8_t>(k)};
            t += 1000;
            REQUIRE(bus::publish(*w, k % 3 ? "IN" : "NOISE", m));
        }
    }
    for (const char* out : {"a.lcm", "b.lcm"})
        REQUIRE(test::run({test::bin("ugv-test-daemon"), "--replay", dir / "in.lcm", "--out", dir / out}, dir / "o",
                          dir / "e") == 0);
    const std::string a = test::read_file(dir / "a.lcm");
    CHECK(!a.empty());
    CHECK(a == test::read_file(dir / "b.lcm"));
    auto r = bus::open_log_replay(dir / "a.lcm");
    std::vector<int64_t> seqs;
    bus::subscribe<raw_bytes_t>(*r, "OUT", [&](const std::string&, const raw_bytes_t& m, int64_t) { seqs.push_back(m.seq); });
    while (r->handle(0) == bus::HandleResult::handled) {
    }
    REQUIRE(seqs.size() == 66);
    CHECK(seqs[0] == 2);
    CHECK(seqs[1] == 4);
    CHECK(seqs[2] == 8);
}

TEST_CASE("daemon: live input, taken as it arrives or batched (bus_batch_ms), loses nothing and keeps the order")
{
    // 300 messages in bursts of 20, many batches' worth: every one must be echoed, in order,
    // whether the daemon wakes per message or drains the bus every 25 ms. (The bursts are
    // paced so that a batch fits the kernel's receive buffer on a host without the .deb's
    // sysctl: there the buffer is the queue, see docs/deploy.md.)
    int port = 7613;
    for (const int batch_ms : {0, 25}) {
        CAPTURE(batch_ms);
        test::TempDir dir;
        const std::string url = test::lcm_url(port++);
        test::write_file(dir / "d.toml", "echo = true\nbus_batch_ms = " + std::to_string(batch_ms) + "\n");
        auto bus = bus::open_live(url);
        std::vector<int64_t> echoed;
        std::vector<daemon_status_t> status;
        bus::subscribe<raw_bytes_t>(*bus, "OUT", [&](const std::string&, const raw_bytes_t& m, int64_t) { echoed.push_back(m.seq); });
        bus::subscribe<daemon_status_t>(*bus, "STATUS_DAEMON", [&](const std::string&, const daemon_status_t& m, int64_t) {
            status.push_back(m);
        });
        test::Process d({test::bin("ugv-test-daemon"), "--config", dir / "d.toml", "--lcm-url", url}, dir / "out", dir / "err");
        REQUIRE(test::wait_until([&] { bus->handle(20); return !status.empty(); }, 10));
        for (int k = 0; k < 300; ++k) {
            raw_bytes_t m{};
            m.seq = k;
            m.device = "in";
            REQUIRE(bus::publish(*bus, "IN", m));
            if (k % 20 == 19) bus->handle(10);
        }
        test::wait_until([&] { bus->handle(20); return echoed.size() >= 300; }, 10);
        std::vector<int64_t> expected;
        for (int k = 0; k < 300; ++k) expected.push_back(2 * k);
        CHECK(echoed == expected);
        const std::size_t seen = status.size();
        REQUIRE(test::wait_until([&] { bus->handle(20); return status.size() > seen; }, 5));
        const daemon_status_t& s = status.back();
        std::map<std::string, int64_t> counters;
        for (int k = 0; k < s.ncounters; ++k) counters[s.counter_names[k]] = s.counter_values[k];
        CHECK(counters.at("bus_incomplete_messages") == 0);
        CHECK(counters.at("bus_invalid_datagrams") == 0);
        d.signal(SIGTERM);
        CHECK(d.wait_exit(2.0) == 0);
    }
}

TEST_CASE("daemon: no output by startup_timeout_s -> DEGRADED naming the output, never RUNNING, watchdog fed")
{
    // Issue 23, "STATUS tells the truth": the mechanism every daemon uses (port 7749).
    test::TempDir dir;
    const std::string url = test::lcm_url(7749);
    auto listen = bus::open_live(url);
    std::vector<daemon_status_t> status;
    bus::subscribe<daemon_status_t>(*listen, "STATUS_DAEMON", [&](const std::string&, const daemon_status_t& m, int64_t) {
        status.push_back(m);
    });
    const auto state_is = [&](int8_t s) { return !status.empty() && status.back().state == s; };
    test::NotifySocket notify(dir / "notify");
    test::write_file(dir / "d.toml", "healthy = false\nstartup_timeout_s = 1\n");
    test::Process d({test::bin("ugv-test-daemon"), "--config", dir / "d.toml", "--lcm-url", url}, dir / "out",
                    dir / "err", {notify.env(), "WATCHDOG_USEC=400000"});
    INFO(d.err());
    REQUIRE(test::wait_until([&] { listen->handle(20); return !status.empty(); }, 10));
    CHECK(status.front().state == daemon_status_t::STATE_STARTING);
    REQUIRE(test::wait_until([&] { listen->handle(20); return state_is(daemon_status_t::STATE_DEGRADED); }, 5));
    CHECK(status.back().last_error == "no output within startup_timeout_s = 1 s of start");
    for (const auto& s : status) CHECK(s.state != daemon_status_t::STATE_RUNNING);
    // READY=1 came (it called ready(); a daemon that never does gets it at the deadline), and a
    // processing daemon waiting for output is fed: a restart would not bring its inputs back.
    CHECK(notify.wait_for("READY=1", 2));
    CHECK(notify.wait_for("WATCHDOG=1", 2));
    d.signal(SIGTERM);
    CHECK(d.wait_exit(2.0) == 0);
}
