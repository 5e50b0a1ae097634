// STATUS tells the truth (issue 23): RUNNING only while the daemon's output flows, DEGRADED
// with the reason when its inputs stop or its device gives only garbage, STARTING only until
// startup_timeout_s. Real daemons on real LCM, ports 7740-7742 and 7745-7746 (ugv-lms's case
// is in test_lms_faults, ugv-pose's in test_pose_daemon).
#include <catch2/catch.hpp>

#include <cmath>
#include <csignal>
#include <filesystem>
#include <numbers>
#include <string>

#include <ugv/imu_t.hpp>
#include <ugv/laser_scan_t.hpp>
#include <ugv/point_cloud_t.hpp>
#include <ugv/servo_state_t.hpp>
#include <ugv/terrain_map_t.hpp>

#include "status_rig.hpp"
#include "terrain_feed.hpp"

using namespace ugv;
using namespace ugv::test;
using namespace ugv::test::status;

namespace {

std::unique_ptr<Process> start_daemon(const TempDir& dir, const std::string& program, const std::string& config,
                                      int port)
{
    write_file(dir / "d.toml", config);
    return std::make_unique<Process>(
        std::vector<std::string>{bin(program), "--config", dir / "d.toml", "--lcm-url", lcm_url(port)}, dir / "d.out",
        dir / "d.err");
}

void stop(Process& p)
{
    CHECK(p.running());
    p.signal(SIGTERM);
    CHECK(p.wait_exit(5.0) == 0);
}

}  // namespace

TEST_CASE("ugv-imu fed only garbage leaves STARTING for DEGRADED at startup_timeout_s, naming why", "[status][imu]")
{
    TempDir dir;
    const std::string pty = dir / "imu";
    // The unit talks at 19200 baud, the daemon listens at 38400: everything it reads is noise.
    Process sim({bin("ugv-sim"), "imu", "--pty", pty, "--baud", "19200", "--streaming"}, dir / "sim.out",
                dir / "sim.err");
    REQUIRE(wait_until([&] { return std::filesystem::exists(pty); }, 10.0));
    Listener l(lcm_url(7740), "STATUS_IMU");
    int samples = 0;
    bus::subscribe<imu_t>(l.bus(), "IMU", [&](const std::string&, const imu_t&, int64_t) { ++samples; });
    auto d = start_daemon(dir, "ugv-imu", "device = \"" + pty + "\"\nbaud = 38400\nstartup_timeout_s = 3\n", 7740);
    INFO(d->err());
    REQUIRE(l.until([&] { return !l.states.empty(); }, 10.0));
    CHECK(l.states.front() == kStarting);
    REQUIRE(l.until([&] { return l.state_is(kDegraded); }, 15.0));
    CHECK(l.error_has("no samples on IMU within startup_timeout_s = 3 s"));
    CHECK(l.error_has("at 38400 baud"));
    // And it stays so: no flapping while nothing flows.
    l.for_seconds(4.0);
    CHECK(l.state_is(kDegraded));
    CHECK_FALSE(l.saw(kRunning));
    CHECK(samples == 0);
    stop(*d);
}

TEST_CASE("ugv-nodscan: RUNNING while POINTS flow, DEGRADED when its inputs stop, RUNNING when they resume",
          "[status][nodscan]")
{
    TempDir dir;
    Listener l(lcm_url(7741), "STATUS_NODSCAN");
    int clouds = 0;
    bus::subscribe<point_cloud_t>(l.bus(), "POINTS", [&](const std::string&, const point_cloud_t&, int64_t) { ++clouds; });
    auto d = start_daemon(dir, "ugv-nodscan", "", 7741);
    INFO(d->err());
    REQUIRE(l.until([&] { return !l.states.empty(); }, 10.0));

    int64_t servo_seq = 0, scan_seq = 0;
    Every servo_every(10'000), scan_every(26'667);
    const auto feed = [&] {
        servo_every([&] {
            servo_state_t s{};
            s.utime = io::now_utime();
            s.seq = servo_seq++;
            s.angle = 0.35;
            s.cia402_state = servo_state_t::STATE_OPERATION_ENABLED;
            bus::publish(l.bus(), "SERVO_STATE", s);
        });
        scan_every([&] {
            laser_scan_t s{};
            s.utime = io::now_utime() - 20'000;  // its last beam 13 ms later: bracketed by the servo
            s.seq = scan_seq++;
            s.sensor_id = "front";
            s.angle_min = static_cast<float>(-std::numbers::pi / 2);
            s.angle_increment = static_cast<float>(std::numbers::pi / 180);
            s.time_increment = static_cast<float>(13.333e-3 / 180);
            s.scan_period = 26.667e-3f;
            s.range_max = 81.0f;
            s.nranges = 181;
            s.ranges.assign(181, 3.0f);
            s.flags.assign(181, laser_scan_t::FLAG_OK);
            bus::publish(l.bus(), "LMS_SCAN", s);
        });
    };
    REQUIRE(l.until([&] { return l.state_is(kRunning) && clouds > 20; }, 15.0, feed));
    // The inputs stop: no POINTS, and the state says so within the 2 s stall time and a status,
    // and stays so.
    REQUIRE(l.until([&] { return l.state_is(kDegraded); }, 6.0));
    CHECK(l.error_has("no POINTS for 2.0 s"));
    const std::size_t from = l.states.size();
    l.for_seconds(2.0);
    CHECK_FALSE(l.saw_since(from, kRunning));
    // They resume.
    REQUIRE(l.until([&] { return l.state_is(kRunning); }, 6.0, feed));
    stop(*d);
}

TEST_CASE("ugv-terrain: RUNNING only while new points update the map; DEGRADED when they stop, maps or not",
          "[status][terrain]")
{
    TempDir dir;
    Listener l(lcm_url(7742), "STATUS_TERRAIN");
    int maps = 0;
    bus::subscribe<terrain_map_t>(l.bus(), "TERRAIN_MAP", [&](const std::string&, const terrain_map_t&, int64_t) { ++maps; });
    auto d = start_daemon(dir, "ugv-terrain", small_map_config() + "health_timeout_s = 1.0\n", 7742);
    INFO(d->err());
    REQUIRE(l.until([&] { return !l.states.empty(); }, 10.0));
    TerrainFeed feed;
    Every pose_every(100'000), cloud_every(100'000);
    const auto both = [&] {
        pose_every([&] { feed.pose(l.bus()); });
        cloud_every([&] { feed.cloud(l.bus()); });
    };
    const auto pose_only = [&] { pose_every([&] { feed.pose(l.bus()); }); };
    REQUIRE(l.until([&] { return l.state_is(kRunning) && maps > 5; }, 15.0, both));

    // Points stop, poses go on: maps are still published, but nothing new is in them.
    const int maps_before = maps;
    REQUIRE(l.until([&] { return l.state_is(kDegraded); }, 5.0, pose_only));
    CHECK(l.error_has("no maps updated by new points on TERRAIN_MAP for 1.0 s"));
    l.for_seconds(2.0, pose_only);
    CHECK(maps > maps_before + 3);
    CHECK(l.state_is(kDegraded));

    REQUIRE(l.until([&] { return l.state_is(kRunning); }, 6.0, both));
    // Everything stops.
    REQUIRE(l.until([&] { return l.state_is(kDegraded); }, 5.0));
    REQUIRE(l.until([&] { return l.state_is(kRunning); }, 6.0, both));
    stop(*d);
}
