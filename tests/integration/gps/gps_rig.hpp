// What the ugv-gps integration tests share: the traffic seen on the test's LCM port, a
// listener pumping it, the emulator + daemon pair on a pty (Rig), and the emulator's exact
// position (--noise 0) that every published fix must equal.
#pragma once

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <ugv/daemon_status_t.hpp>
#include <ugv/gps_fix_t.hpp>
#include <ugv/gps_velocity_t.hpp>

#include "ugv/bus/typed.hpp"
#include "ugv/io/clock.hpp"
#include "ugv_test/process.hpp"

namespace ugv::test::gps {

constexpr double kLat = 50.25, kLon = -110.5;  // the emulator's position (--noise 0)

struct Traffic
{
    std::mutex m;
    std::vector<ugv::gps_fix_t> fixes;
    std::vector<int64_t> fix_recv;
    std::vector<ugv::gps_velocity_t> vels;
    std::vector<ugv::daemon_status_t> status;

    std::size_t nfix()
    {
        std::lock_guard<std::mutex> l(m);
        return fixes.size();
    }
    int64_t counter(const std::string& name)
    {
        std::lock_guard<std::mutex> l(m);
        if (status.empty()) return -1;
        const auto& s = status.back();
        for (int i = 0; i < s.ncounters; ++i) {
            if (s.counter_names[i] == name) return s.counter_values[i];
        }
        return -1;
    }
    bool saw_state(int8_t state)
    {
        std::lock_guard<std::mutex> l(m);
        for (const auto& s : status) {
            if (s.state == state) return true;
        }
        return false;
    }
};

// Bus listener on the test's own port; handle() is pumped by wait().
struct Listener
{
    std::unique_ptr<ugv::bus::Bus> bus;
    Traffic t;
    explicit Listener(int port) : bus(ugv::bus::open_live(ugv::test::lcm_url(port)))
    {
        ugv::bus::subscribe<ugv::gps_fix_t>(*bus, "GPS_FIX", [this](const std::string&, const ugv::gps_fix_t& f, int64_t r) {
            std::lock_guard<std::mutex> l(t.m);
            t.fixes.push_back(f);
            t.fix_recv.push_back(r);
        });
        ugv::bus::subscribe<ugv::gps_velocity_t>(*bus, "GPS_VEL", [this](const std::string&, const ugv::gps_velocity_t& v, int64_t) {
            std::lock_guard<std::mutex> l(t.m);
            t.vels.push_back(v);
        });
        ugv::bus::subscribe<ugv::daemon_status_t>(*bus, "STATUS_GPS", [this](const std::string&, const ugv::daemon_status_t& s, int64_t) {
            std::lock_guard<std::mutex> l(t.m);
            t.status.push_back(s);
        });
    }
    template <typename Pred>
    bool wait(Pred pred, double timeout_s)
    {
        const int64_t end = ugv::io::monotonic_us() + static_cast<int64_t>(timeout_s * 1e6);
        while (!pred() && ugv::io::monotonic_us() < end) {
            bus->handle(20);
        }
        return pred();
    }
};

struct Rig
{
    TempDir dir;
    std::string pty;
    std::unique_ptr<Process> sim;
    std::unique_ptr<Process> daemon;
    Rig() : pty(dir / "gps") {}

    void start_sim(std::vector<std::string> extra)
    {
        std::vector<std::string> argv = {ugv::test::bin("ugv-sim"), "gps", "--pty", pty, "--noise", "0",
                                         "--lat", std::to_string(kLat), "--lon", std::to_string(kLon)};
        argv.insert(argv.end(), extra.begin(), extra.end());
        sim = std::make_unique<Process>(argv, dir / "sim.out", dir / "sim.err");
        REQUIRE(ugv::test::wait_until([&] { return std::filesystem::exists(pty); }, 10.0));
    }
    void start_daemon(const std::string& toml, int port)
    {
        ugv::test::write_file(dir / "gps.toml", "device = \"" + pty + "\"\n" + toml);
        daemon = std::make_unique<Process>(
            std::vector<std::string>{ugv::test::bin("ugv-gps"), "--config", dir / "gps.toml", "--lcm-url",
                                     ugv::test::lcm_url(port)},
            dir / "gps.out", dir / "gps.err");
    }
    ~Rig()
    {
        if (daemon) {
            daemon->signal(SIGTERM);
            daemon->wait_exit(5.0);
        }
        if (sim) {
            sim->signal(SIGTERM);
            sim->wait_exit(5.0);
        }
    }
    std::string logs() const
    {
        return "--- ugv-gps stderr:\n" + (daemon ? daemon->err() : std::string()) + "--- ugv-sim stderr:\n" +
               (sim ? sim->err() : std::string());
    }
};

inline void check_position(const ugv::gps_fix_t& f)
{
    CHECK_THAT(f.latitude, Catch::Matchers::WithinAbs(kLat, 1e-7));
    CHECK_THAT(f.longitude, Catch::Matchers::WithinAbs(kLon, 1e-7));
    CHECK_THAT(f.height, Catch::Matchers::WithinAbs(750.0 - 17.0, 1e-3));  // MSL + undulation
}

}  // namespace ugv::test::gps
