// Two hosts of one vehicle, one with its clock 1 s ahead (UGV_CLOCK_OFFSET_S, the test aid of
// io/clock.hpp): host B reads the GPS receiver and the IMU (ugv-gps, ugv-imu on the emulators),
// host A runs ugv-pose and ugv-terrain. With both clocks right, no flag; with B's clock ahead,
// ugv-pose flags IMU (its stamps are B's clock; the fixes carry GPS time), ugv-terrain flags
// POSE (stamped from the IMU's time), each within 2 s of the first offset message reaching A,
// and ugv-gps on B reports its host's offset from GPS time.
//
// As root the two hosts are two network namespaces joined by a veth pair (LCM ttl=1, as
// tests/bench/netns-two-host.sh); this process joins host A's. Otherwise both groups run on
// this host (ttl=0), which the output says.
#include <catch2/catch.hpp>

#include <fcntl.h>
#include <sched.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <ugv/daemon_status_t.hpp>
#include <ugv/imu_t.hpp>
#include <ugv/pose_t.hpp>

#include "ugv/bus/typed.hpp"
#include "ugv/io/clock.hpp"
#include "ugv_test/process.hpp"

using namespace ugv;
using ugv::test::bin;
using ugv::test::Process;

namespace {

constexpr int kPort = 7914;
constexpr int64_t kOffsetUs = 1'000'000;

int64_t counter(const daemon_status_t& s, const std::string& name)
{
    for (int i = 0; i < s.ncounters; ++i)
        if (s.counter_names[static_cast<std::size_t>(i)] == name) return s.counter_values[static_cast<std::size_t>(i)];
    return -999;
}

// Host A and host B: two network namespaces with a veth pair, or nothing (this host).
class Hosts
{
public:
    Hosts()
    {
        if (::geteuid() != 0) return;
        const std::string id = std::to_string(::getpid());
        a_ = "ugv-t29a-" + id;
        b_ = "ugv-t29b-" + id;
        const std::string va = "ugvta" + id, vb = "ugvtb" + id;
        const std::string script =
            "set -e; ip netns add " + a_ + "; ip netns add " + b_ + "; ip link add " + va + " netns " + a_ +
            " type veth peer name " + vb + " netns " + b_ + "; ip -n " + a_ + " addr add 10.254.77.1/24 dev " + va +
            "; ip -n " + b_ + " addr add 10.254.77.2/24 dev " + vb + "; for h in " + a_ + ":" + va + " " + b_ + ":" + vb +
            "; do ip -n ${h%:*} link set lo up; ip -n ${h%:*} link set ${h#*:} up; ip -n ${h%:*} route add "
            "239.255.76.67/32 dev ${h#*:}; done";
        if (std::system(("(" + script + ") >/dev/null 2>&1").c_str()) != 0) {
            cleanup();
            return;
        }
        // This process (single-threaded here) joins A: its LCM socket is host A's.
        const int fd = ::open(("/run/netns/" + a_).c_str(), O_RDONLY | O_CLOEXEC);
        if (fd < 0 || ::setns(fd, CLONE_NEWNET) != 0) {
            if (fd >= 0) ::close(fd);
            cleanup();
            return;
        }
        ::close(fd);
        netns_ = true;
    }
    ~Hosts() { cleanup(); }
    bool netns() const { return netns_; }
    std::string url() const
    {
        return "udpm://239.255.76.67:" + std::to_string(kPort) + (netns_ ? "?ttl=1" : "?ttl=0");
    }
    // argv run on host B (A is this process's namespace, inherited).
    std::vector<std::string> on_b(std::vector<std::string> argv) const
    {
        if (!netns_) return argv;
        std::vector<std::string> out = {"/usr/sbin/ip", "netns", "exec", b_};
        if (!std::filesystem::exists(out[0])) out[0] = "/sbin/ip";
        out.insert(out.end(), argv.begin(), argv.end());
        return out;
    }

private:
    void cleanup()
    {
        if (a_.empty()) return;
        // The namespaces go with their last process; the veth pair with them.
        std::system(("ip netns del " + a_ + " >/dev/null 2>&1; ip netns del " + b_ + " >/dev/null 2>&1").c_str());
        a_.clear();
    }
    std::string a_, b_;
    bool netns_ = false;
};

struct Seen
{
    std::optional<int64_t> first_offset_imu_us;  // arrival (A's clock) of the first IMU stamped ahead
    std::map<std::string, std::vector<std::pair<int64_t, daemon_status_t>>> status;  // channel -> (arrival, msg)
    int64_t imu = 0, pose = 0;
};

void stop(std::unique_ptr<Process>& p)
{
    if (!p) return;
    p->signal(SIGTERM);
    p->wait_exit(5.0);
    p.reset();
}

}  // namespace

TEST_CASE("clock offset on one host: ugv-pose and ugv-terrain flag it within 2 s, ugv-gps reports it")
{
    Hosts hosts;
    std::printf("test_clock_offset_hosts: %s\n",
                hosts.netns() ? "two network namespaces joined by a veth pair (LCM ttl=1)"
                              : "two groups of processes on this host (not root: no network namespaces)");
    test::TempDir dir;
    const std::string url = hosts.url();
    auto bus = bus::open_live(url);
    Seen seen;
    bus::subscribe<imu_t>(*bus, "IMU", [&](const std::string&, const imu_t& m, int64_t recv) {
        ++seen.imu;
        if (!seen.first_offset_imu_us && m.utime - recv > kOffsetUs / 2) seen.first_offset_imu_us = recv;
    });
    bus::subscribe<pose_t>(*bus, "POSE", [&](const std::string&, const pose_t&, int64_t) { ++seen.pose; });
    for (const char* ch : {"STATUS_POSE", "STATUS_TERRAIN", "STATUS_GPS"})
        bus::subscribe<daemon_status_t>(*bus, ch, [&](const std::string& c, const daemon_status_t& s, int64_t recv) {
            seen.status[c].emplace_back(recv, s);
        });
    const auto pump = [&](double seconds, auto pred) {
        const int64_t end = io::monotonic_us() + static_cast<int64_t>(seconds * 1e6);
        while (!pred() && io::monotonic_us() < end) bus->handle(20);
        return pred();
    };

    // The devices (pseudo-terminals: no network).
    const std::string gps_pty = dir / "gps", imu_pty = dir / "imu";
    Process sim_gps({bin("ugv-sim"), "gps", "--pty", gps_pty}, dir / "sim-gps.out", dir / "sim-gps.err");
    Process sim_imu({bin("ugv-sim"), "imu", "--pty", imu_pty}, dir / "sim-imu.out", dir / "sim-imu.err");
    REQUIRE(test::wait_until([&] { return std::filesystem::exists(gps_pty) && std::filesystem::exists(imu_pty); }, 10));
    test::write_file(dir / "gps.toml", "device = \"" + gps_pty + "\"\n");
    test::write_file(dir / "imu.toml", "device = \"" + imu_pty + "\"\n");
    test::write_file(dir / "empty.toml", "");

    // Host A: no offset.
    const auto daemon_argv = [&](const std::string& name, const std::string& config) {
        return std::vector<std::string>{bin(name), "--config", dir / config, "--lcm-url", url};
    };
    Process pose(daemon_argv("ugv-pose", "empty.toml"), dir / "pose.out", dir / "pose.err", {"UGV_CLOCK_OFFSET_S=0"});
    Process terrain(daemon_argv("ugv-terrain", "empty.toml"), dir / "terrain.out", dir / "terrain.err",
                    {"UGV_CLOCK_OFFSET_S=0"});
    // Host B: first with its clock right.
    std::unique_ptr<Process> gps, imu;
    const auto start_b = [&](int64_t offset_us, const std::string& tag) {
        const std::string env = "UGV_CLOCK_OFFSET_S=" + std::to_string(static_cast<double>(offset_us) * 1e-6);
        gps = std::make_unique<Process>(hosts.on_b(daemon_argv("ugv-gps", "gps.toml")), dir / ("gps" + tag + ".out"),
                                        dir / ("gps" + tag + ".err"), std::vector<std::string>{env});
        imu = std::make_unique<Process>(hosts.on_b(daemon_argv("ugv-imu", "imu.toml")), dir / ("imu" + tag + ".out"),
                                        dir / ("imu" + tag + ".err"), std::vector<std::string>{env});
    };
    const auto logs = [&] {
        std::string s;
        for (const char* f : {"pose.err", "terrain.err", "gps1.err", "imu1.err", "gps2.err", "imu2.err"})
            s += std::string("--- ") + f + ":\n" + test::read_file(dir / f);
        return s;
    };
    start_b(0, "1");

    // 1. Clocks agree: POSE flows; the STATUS messages after that carry no flag.
    const bool flowing = pump(30, [&] { return seen.pose >= 20 && seen.status["STATUS_GPS"].size() >= 2; });
    INFO(logs());
    REQUIRE(flowing);
    const std::size_t pose_from = seen.status["STATUS_POSE"].size(), terrain_from = seen.status["STATUS_TERRAIN"].size();
    REQUIRE(pump(10, [&] {
        return seen.status["STATUS_POSE"].size() >= pose_from + 2 && seen.status["STATUS_TERRAIN"].size() >= terrain_from + 2;
    }));
    for (const char* ch : {"STATUS_POSE", "STATUS_TERRAIN"}) {
        for (const auto& [recv, s] : seen.status[ch]) {
            INFO(ch << " seq " << s.seq);
            CHECK(counter(s, "clock_skew") == 0);
            CHECK(counter(s, "clock_skew_events") == 0);
            CHECK(counter(s, "host_clock_test_offset_us") == 0);
        }
    }
    const daemon_status_t gps_right = seen.status["STATUS_GPS"].back().second;
    CHECK(counter(gps_right, "host_clock_offset_valid") == 1);
    const int64_t right_offset = counter(gps_right, "host_clock_offset_us");
    std::printf("clocks agree: ugv-gps host_clock_offset_us %lld\n", static_cast<long long>(right_offset));
    // The emulator writes each frame at once, where a receiver sends it at the line's rate: the
    // transmission time the daemon takes off (~0.1-0.2 s at 9600 baud) reads as the host behind.
    CHECK(std::llabs(right_offset) < 300'000);
    CHECK(!seen.first_offset_imu_us);

    // 2. Host B's clock 1 s ahead (its daemons restarted with the offset).
    stop(gps);
    stop(imu);
    seen.status["STATUS_GPS"].clear();
    start_b(kOffsetUs, "2");
    REQUIRE(pump(20, [&] { return seen.first_offset_imu_us.has_value(); }));
    const int64_t t0 = *seen.first_offset_imu_us;
    const auto first_flag = [&](const char* ch) -> std::optional<std::pair<int64_t, daemon_status_t>> {
        for (const auto& [recv, s] : seen.status[ch])
            if (recv >= t0 && counter(s, "clock_skew") == 1) return std::make_pair(recv, s);
        return std::nullopt;
    };
    // Bounded well past the goal: the figure is measured below, on arrivals.
    pump(6, [&] {
        return first_flag("STATUS_POSE") && first_flag("STATUS_TERRAIN") && !seen.status["STATUS_GPS"].empty() &&
               counter(seen.status["STATUS_GPS"].back().second, "host_clock_offset_valid") == 1;
    });
    const auto pose_flag = first_flag("STATUS_POSE"), terrain_flag = first_flag("STATUS_TERRAIN");
    REQUIRE(pose_flag);
    REQUIRE(terrain_flag);
    const double pose_s = static_cast<double>(pose_flag->first - t0) * 1e-6;
    const double terrain_s = static_cast<double>(terrain_flag->first - t0) * 1e-6;
    std::printf("B 1 s ahead: ugv-pose flags IMU %.3f s, ugv-terrain flags POSE %.3f s after the first offset IMU "
                "message reached A; clock_skew_us %lld and %lld\n",
                pose_s, terrain_s, static_cast<long long>(counter(pose_flag->second, "clock_skew_us")),
                static_cast<long long>(counter(terrain_flag->second, "clock_skew_us")));
    // The goal: within 2 s (two STATUS periods: the flag at the first message, STATUS once a second).
    CHECK(pose_s <= 2.0);
    CHECK(terrain_s <= 2.0);
    // Each says how far ahead: the IMU by the whole second (at least that much: minus its
    // latency); the poses by the second less ugv-pose's reorder buffer (up to 0.4 s).
    CHECK(counter(pose_flag->second, "clock_skew_us") > 800'000);
    CHECK(counter(pose_flag->second, "clock_skew_us") <= kOffsetUs + 20'000);
    CHECK(counter(terrain_flag->second, "clock_skew_us") > 200'000);
    CHECK(counter(terrain_flag->second, "clock_skew_us") <= kOffsetUs + 20'000);
    CHECK(counter(pose_flag->second, "clock_skew_events") >= 1);
    // ugv-gps on B: its host's clock 1 s ahead of GPS time, and the test aid in effect.
    REQUIRE_FALSE(seen.status["STATUS_GPS"].empty());
    const daemon_status_t gps_ahead = seen.status["STATUS_GPS"].back().second;
    CHECK(counter(gps_ahead, "host_clock_offset_valid") == 1);
    const int64_t ahead_offset = counter(gps_ahead, "host_clock_offset_us");
    std::printf("B 1 s ahead: ugv-gps host_clock_offset_us %lld\n", static_cast<long long>(ahead_offset));
    CHECK(std::llabs(ahead_offset - right_offset - kOffsetUs) < 30'000);  // moved by the offset
    CHECK(counter(gps_ahead, "host_clock_test_offset_us") == kOffsetUs);
    // The inputs were taken, not refused: 1 s is within max_stamp_ahead_s (2 s).
    CHECK(counter(pose_flag->second, "stamps_ahead") == 0);

    stop(gps);
    stop(imu);
    for (Process* p : {&pose, &terrain}) {
        p->signal(SIGTERM);
        CHECK(p->wait_exit(5.0) == 0);
    }
}
