// ugv-nodscan's adapter: a scan waits for a servo sample that brackets its last beam, but
// only a bounded time (of message time); the configuration is validated.
#include <catch2/catch.hpp>

#include <cmath>
#include <utility>
#include <vector>

#include "nodscan_node.hpp"
#include "ugv/runtime/config.hpp"

using namespace ugv;
using nodscan_daemon::NodscanNode;

namespace {

laser_scan_t scan(int64_t utime, int n = 11, float range = 2.0f)
{
    laser_scan_t s{};
    s.utime = utime;
    s.sensor_id = "front";
    s.angle_min = 0.0f;
    s.angle_increment = 0.01f;
    s.time_increment = 0.001f;  // 10 ms from first to last beam with 11 beams
    s.range_max = 80.0f;
    s.nranges = n;
    s.ranges.assign(static_cast<std::size_t>(n), range);
    s.flags.assign(static_cast<std::size_t>(n), 0);
    return s;
}

servo_state_t servo(int64_t utime, double angle)
{
    servo_state_t m{};
    m.utime = utime;
    m.angle = angle;
    return m;
}

nodscan_daemon::NodscanConfig config()
{
    auto cfg = runtime::Config::parse("max_wait_ms = 50\nmax_extrapolation_ms = 2\n[mount]\ntilt_axis_xyz_m = [0.0, 0.0, 1.0]\n");
    auto c = nodscan_daemon::read_config(cfg);
    cfg.finish();
    return c;
}

}  // namespace

TEST_CASE("A scan is assembled once a servo sample at or after its last beam arrived")
{
    std::vector<point_cloud_t> out;
    NodscanNode node(config(), [&](const point_cloud_t& m) { out.push_back(m); });
    node.on_servo(servo(0, 0.2));
    node.on_servo(servo(5'000, 0.2));
    node.on_scan(scan(1'000));  // last beam at 11 ms
    CHECK(out.empty());
    node.on_servo(servo(10'000, 0.2));
    CHECK(out.empty());
    node.on_servo(servo(15'000, 0.2));
    REQUIRE(out.size() == 1);
    CHECK(out[0].npoints == 11);
    CHECK(out[0].utime == 1'000);
    CHECK(out[0].sensor_id == "front");
    CHECK(out[0].z[0] == Approx(1.0 - 2.0 * std::sin(0.2)).margin(1e-6));
    CHECK(node.counters().dropped_no_angle == 0);
}

TEST_CASE("Without servo samples a scan waits max_wait of message time, then goes with what there is")
{
    std::vector<point_cloud_t> out;
    NodscanNode node(config(), [&](const point_cloud_t& m) { out.push_back(m); });
    node.on_servo(servo(0, 0.1));
    node.on_servo(servo(5'500, 0.1));  // the servo stream stops here
    node.on_scan(scan(1'000));          // beams 1..11 ms: 1..7 ms have angles (to 7.5 ms with 2 ms extrapolation)
    node.on_scan(scan(27'000));         // 27 ms: not yet 50 ms past the first scan's end
    CHECK(out.empty());
    node.on_scan(scan(62'000));  // message time 62 ms > 11 + 50 ms: the first scan goes
    REQUIRE(out.size() == 1);
    CHECK(out[0].npoints == 7);
    CHECK(node.counters().dropped_no_angle == 4);
    // The second has no angle at all: counted, not published.
    node.flush_all();
    CHECK(out.size() == 1);
    CHECK(node.counters().scans_without_servo == 2);
}

TEST_CASE("NaN beams are dropped and counted; other lasers are ignored; bad servo samples rejected")
{
    auto c = config();
    c.sensor_id = "front";
    std::vector<point_cloud_t> out;
    NodscanNode node(c, [&](const point_cloud_t& m) { out.push_back(m); });
    node.on_servo(servo(0, 0.1));
    node.on_servo(servo(0, 0.1));     // not newer
    node.on_servo(servo(1'000, NAN)); // not finite
    CHECK(node.counters().servo_rejected == 2);
    auto s = scan(1'000);
    s.ranges[3] = NAN;
    s.ranges[4] = NAN;
    node.on_scan(s);
    auto other = scan(1'000);
    other.sensor_id = "rear";
    node.on_scan(other);
    CHECK(node.counters().scans_other_sensor == 1);
    node.on_servo(servo(20'000, 0.1));
    REQUIRE(out.size() == 1);
    CHECK(out[0].npoints == 9);
    CHECK(node.counters().dropped_invalid == 2);
    CHECK(out[0].seq == 0);
}

TEST_CASE("A scan whose beam timing is NaN, negative or over 1 s is dropped and counted")
{
    std::vector<point_cloud_t> out;
    NodscanNode node(config(), [&](const point_cloud_t& m) { out.push_back(m); });
    node.on_servo(servo(0, 0.2));
    node.on_servo(servo(50'000, 0.2));
    for (float dt : {NAN, -0.001f, 0.2f, 3e38f}) {  // 0.2 s x 10 beams = 2 s
        laser_scan_t s = scan(1'000);
        s.time_increment = dt;
        node.on_scan(s);
    }
    CHECK(node.counters().scans_bad_timing == 4);
    CHECK(node.counters().scans_in == 4);
    node.on_scan(scan(2'000));
    node.on_servo(servo(60'000, 0.2));
    CHECK(out.size() == 1);  // the good one, and only it
}

TEST_CASE("An interlaced scan waits for its last measured beam; a broken sweep layout is dropped")
{
    std::vector<point_cloud_t> out;
    NodscanNode node(config(), [&](const point_cloud_t& m) { out.push_back(m); });
    node.on_servo(servo(0, 0.2));
    node.on_servo(servo(12'000, 0.2));
    // 11 beams, 1 ms per index, 2 sweeps 20 ms apart, even beams second: beam 10 at 1 + 30 ms.
    laser_scan_t s = scan(1'000);
    s.nsweeps = 2;
    s.sweep_order = {1, 0};
    s.sweep_period = 0.020f;
    node.on_scan(s);
    node.on_servo(servo(25'000, 0.2));
    CHECK(out.empty());  // beam 9 (odd: 10 ms) is bracketed, beam 10 (31 ms) is not
    node.on_servo(servo(31'000, 0.2));
    REQUIRE(out.size() == 1);
    CHECK(out[0].time_offset[10] == Approx(0.030));
    CHECK(out[0].time_offset[9] == Approx(0.009));
    for (const auto& [order, period] : {std::pair<std::vector<int8_t>, float>{{0, 0}, 0.02f},
                                        {{0, 2}, 0.02f}, {{1, 0}, NAN}, {{1, 0}, 2.0f}}) {
        laser_scan_t bad = s;
        bad.sweep_order = order;
        bad.sweep_period = period;
        node.on_scan(bad);
    }
    CHECK(node.counters().scans_bad_timing == 4);
}

TEST_CASE("ugv-nodscan configuration: mount in degrees, limits checked")
{
    auto cfg = runtime::Config::parse("[mount]\ntilt_axis_rpy_deg = [0.0, 90.0, 0.0]\nlaser_xyz_m = [0.1, 0.0, 0.05]\n");
    const auto c = nodscan_daemon::read_config(cfg);
    CHECK(c.assembler.mount.axis_rpy_rad[1] == Approx(M_PI / 2));
    CHECK(c.assembler.mount.laser_xyz_m[0] == 0.1);
    CHECK(c.assembler.mount.axis_xyz_m[2] == 0.87);  // default height
    auto bad = runtime::Config::parse("max_wait_ms = 1500\nservo_history_ms = 2000\n", "bad.toml");
    CHECK_THROWS_WITH(nodscan_daemon::read_config(bad), Catch::Contains("servo_history_ms"));
}
