// Issue 23, time sanity: the real ugv-pose, ugv-nodscan and ugv-terrain live on LCM (ports
// 7720-7722), fed good traffic in real time stamped from the wall clock, with one message
// of each bad stamp on each input (INT64_MAX, INT64_MIN, a year ahead, an hour back, older
// than the daemon's history, and INT64_MAX followed by a year ahead). Each is refused and
// counted, the output's message time goes on without a gap (the next output comes one
// period later), and RSS stays within a few MB. Then one input is stamped a year ahead for
// 3 s: the daemon says DEGRADED naming it, and RUNNING once good stamps are back.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <ugv/daemon_status_t.hpp>
#include <ugv/gps_fix_t.hpp>
#include <ugv/gps_velocity_t.hpp>
#include <ugv/imu_t.hpp>
#include <ugv/laser_scan_t.hpp>
#include <ugv/point_cloud_t.hpp>
#include <ugv/pose_t.hpp>
#include <ugv/servo_state_t.hpp>
#include <ugv/terrain_map_t.hpp>

#include "../terrain/synthetic_log.hpp"
#include "live_daemon.hpp"

using namespace ugv;

namespace {

constexpr int64_t kYearUs = 365LL * 86'400'000'000LL;
constexpr int64_t kHourUs = 3'600'000'000LL;

int64_t wall_us()
{
    return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::system_clock::now().time_since_epoch())
        .count();
}

int64_t rss_kb(pid_t pid)
{
    std::ifstream in("/proc/" + std::to_string(pid) + "/status");
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("VmRSS:", 0) == 0) return std::stoll(line.substr(6));
    }
    return -1;
}

// Handles traffic until the wall clock reaches utime (the good stream is real time).
void pace_until(test::LiveDaemon& d, int64_t utime)
{
    while (wall_us() < utime) d.pump(0.002);
}

struct BadStamp
{
    std::string name;
    std::function<int64_t(int64_t t)> stamp;  // from the good stream's time t
    bool ahead;
};

// The cases; `older_than_history_us`: how far back the daemon's history reaches.
std::vector<BadStamp> bad_stamps(int64_t older_than_history_us)
{
    return {
        {"INT64_MAX", [](int64_t) { return std::numeric_limits<int64_t>::max(); }, true},
        {"INT64_MIN", [](int64_t) { return std::numeric_limits<int64_t>::min(); }, false},
        {"a year ahead", [](int64_t t) { return t + kYearUs; }, true},
        {"an hour back", [](int64_t t) { return t - kHourUs; }, false},
        {"older than the history", [=](int64_t t) { return t - older_than_history_us; }, false},
    };
}

// The largest step of message time between `from`, the output times in [from, to), and
// `to`: an output that stops shows as a step up to `to`.
int64_t max_step(const std::vector<int64_t>& utimes, int64_t from, int64_t to)
{
    int64_t prev = from, worst = 0;
    for (int64_t u : utimes) {
        if (u < from || u >= to) continue;
        worst = std::max(worst, u - prev);
        prev = u;
    }
    return std::max(worst, to - prev);
}

// Arrival times of outputs: the largest gap in wall time, s.
struct Arrivals
{
    std::vector<std::chrono::steady_clock::time_point> at;
    double max_gap_s(std::size_t from, std::size_t to = SIZE_MAX) const
    {
        double worst = 0.0;
        for (std::size_t i = from + 1; i < std::min(to, at.size()); ++i)
            worst = std::max(worst, std::chrono::duration<double>(at[i] - at[i - 1]).count());
        return worst;
    }
};

// Waits (with traffic from `step`) for two statuses, so the counters are those after the last message.
void settle(test::LiveDaemon& d, const std::function<void()>& step)
{
    const int statuses = d.statuses();
    for (int k = 0; k < 400 && d.statuses() < statuses + 2; ++k) step();
}

}  // namespace

TEST_CASE("ugv-pose refuses stamps far from its clock on every input; POSE goes on, memory flat")
{
    test::LiveDaemon pose("ugv-pose", "", 7720, "STATUS_POSE");
    std::vector<int64_t> pose_utimes;
    Arrivals arrivals;
    pose.on_decoded<pose_t>("POSE", [&](const pose_t& p) {
        pose_utimes.push_back(p.utime);
        arrivals.at.push_back(std::chrono::steady_clock::now());
    });
    REQUIRE(pose.wait_up(15.0));

    constexpr int64_t kStep = 20'000;  // IMU at 50 Hz; fix and velocity at 5 Hz
    const int64_t t0 = (wall_us() / 100'000 + 2) * 100'000;
    int k = 0;
    bool fix_good = true;
    int64_t t = t0;
    const auto step = [&] {
        t = t0 + k * kStep;
        pace_until(pose, t);
        imu_t m{};
        m.utime = t;
        m.orientation[0] = 1.0;
        m.acceleration[2] = 9.80665;
        m.orientation_sigma = 0.01f;
        m.valid = int32_t{imu_t::VALID_ORIENTATION} | int32_t{imu_t::VALID_ANGULAR_RATE} |
                  int32_t{imu_t::VALID_ACCELERATION};
        pose.publish("IMU", m);
        if (k % 10 == 0) {
            gps_fix_t f{};
            f.utime = fix_good ? t : t + kYearUs;
            f.latitude = 50.27;
            f.longitude = -110.74;
            f.height = 750.0;
            f.sigma_latitude = f.sigma_longitude = 0.5f;
            f.sigma_height = 1.0f;
            f.fix_quality = gps_fix_t::QUALITY_DGPS;
            pose.publish("GPS_FIX", f);
            gps_velocity_t v{};
            v.utime = t;
            pose.publish("GPS_VEL", v);
        }
        ++k;
    };
    const auto steps = [&](int n) {
        for (int i = 0; i < n; ++i) step();
    };
    steps(150);  // 3 s: the filter is up and POSE flows
    const int64_t rss_before = rss_kb(pose.pid());
    const std::size_t arrivals_from = arrivals.at.size();

    int64_t ahead = 0, old = 0;
    const auto bad = [&](const std::string& channel, int64_t stamp) {
        if (channel == "GPS_FIX") {
            gps_fix_t f{};
            f.utime = stamp;
            f.latitude = 50.27;
            f.longitude = -110.74;
            f.fix_quality = gps_fix_t::QUALITY_DGPS;
            pose.publish(channel, f);
        } else if (channel == "GPS_VEL") {
            gps_velocity_t v{};
            v.utime = stamp;
            pose.publish(channel, v);
        } else {
            imu_t m{};
            m.utime = stamp;
            m.orientation[0] = 1.0;
            m.valid = imu_t::VALID_ORIENTATION;
            pose.publish(channel, m);
        }
    };
    for (const BadStamp& c : bad_stamps(3'000'000)) {  // max_stamp_age_s = 2
        for (const char* channel : {"GPS_FIX", "GPS_VEL", "IMU"}) {
            INFO(c.name << " on " << channel);
            bad(channel, c.stamp(t));
            ++(c.ahead ? ahead : old);
            steps(10);
        }
    }
    // What was seen on the vehicle: INT64_MAX, then a year ahead.
    bad("GPS_FIX", std::numeric_limits<int64_t>::max());
    bad("GPS_FIX", t + kYearUs);
    ahead += 2;
    steps(50);
    const int64_t cases_end = t;

    // Every fix a year ahead for 3 s: DEGRADED, naming GPS_FIX; then good fixes: RUNNING.
    fix_good = false;
    bool saw_degraded = false;
    std::string degraded_error;
    for (int i = 0; i < 150; ++i) {
        if (k % 10 == 0) ++ahead;
        step();
        if (pose.state() == daemon_status_t::STATE_DEGRADED && pose.last_error().find("GPS_FIX") != std::string::npos) {
            saw_degraded = true;
            degraded_error = pose.last_error();
        }
    }
    fix_good = true;
    // The vehicle stands still, so the pose's own state is DEGRADED (heading not observed):
    // back means that reason instead of the refused input.
    bool running_again = false;
    for (int i = 0; i < 300 && !running_again; ++i) {
        step();
        running_again = pose.last_error().find("heading not yet observed") != std::string::npos;
    }
    settle(pose, step);
    const int64_t rss_after = rss_kb(pose.pid());

    INFO(pose.stderr_text());
    CHECK(pose.running());
    CHECK(pose.counter("stamps_ahead") == ahead);
    CHECK(pose.counter("stamps_too_old") == old);
    CHECK(pose.counter("late") == 0);  // nothing refused got into the estimator
    CHECK(pose.counter("input_gaps") == 0);
    // The filter never stopped: a POSE after every IMU sample (20 ms of message time) through
    // every case (200 ms allow datagrams lost on the way to this test).
    REQUIRE(pose_utimes.size() > 50);
    const int64_t step_us = max_step(pose_utimes, t0 + 1'000'000, cases_end - 600'000);
    CHECK(step_us <= 200'000);
    const double gap_s = arrivals.max_gap_s(arrivals_from);
    WARN("ugv-pose: largest POSE step " << step_us << " us of message time, largest arrival gap " << gap_s
                                         << " s; RSS " << rss_before << " -> " << rss_after << " kB");
    CHECK(gap_s < 2.0);  // generous: the daemon batches its input every 50 ms, on a loaded machine
    CHECK(rss_after - rss_before < 4096);
    CHECK(saw_degraded);
    INFO("degraded: " << degraded_error);
    CHECK(running_again);
    CHECK(pose.stop() == 0);
}

TEST_CASE("ugv-nodscan refuses stamps far from its clock on SERVO_STATE and LMS_SCAN; POINTS go on")
{
    test::LiveDaemon nodscan("ugv-nodscan", "", 7721, "STATUS_NODSCAN");
    std::vector<int64_t> points_utimes;
    Arrivals arrivals;
    nodscan.on_decoded<point_cloud_t>("POINTS", [&](const point_cloud_t& c) {
        points_utimes.push_back(c.utime);
        arrivals.at.push_back(std::chrono::steady_clock::now());
    });
    REQUIRE(nodscan.wait_up(15.0));

    // Servo at 100 Hz; a scan every third step (30 ms), 181 beams over 13.3 ms, its last beam
    // 6.7 ms before the servo sample published with it (so it is bracketed at once).
    constexpr int64_t kStep = 10'000, kScanPeriod = 30'000, kBeamSpan = 13'333;
    const int64_t t0 = (wall_us() / 100'000 + 2) * 100'000;
    int k = 0;
    bool servo_good = true;
    int64_t t = t0;
    const auto scan_at = [](int64_t utime) {
        laser_scan_t s{};
        s.utime = utime;
        s.sensor_id = "front";
        s.angle_min = static_cast<float>(-std::numbers::pi / 2);
        s.angle_increment = static_cast<float>(std::numbers::pi / 180);
        s.time_increment = static_cast<float>(kBeamSpan * 1e-6 / 180);
        s.scan_period = static_cast<float>(kScanPeriod * 1e-6);
        s.range_max = 81.0f;
        s.nranges = 181;
        s.ranges.assign(181, 5.0f);
        s.flags.assign(181, laser_scan_t::FLAG_OK);
        return s;
    };
    const auto step = [&] {
        t = t0 + k * kStep;
        pace_until(nodscan, t);
        servo_state_t m{};
        m.utime = servo_good ? t : t + kYearUs;
        m.angle = 0.3 + 0.1 * std::sin(static_cast<double>(k) * 0.05);
        m.cia402_state = servo_state_t::STATE_OPERATION_ENABLED;
        nodscan.publish("SERVO_STATE", m);
        if (k % 3 == 0) nodscan.publish("LMS_SCAN", scan_at(t - 20'000));
        ++k;
    };
    const auto steps = [&](int n) {
        for (int i = 0; i < n; ++i) step();
    };
    steps(300);  // 3 s
    const int64_t rss_before = rss_kb(nodscan.pid());
    const std::size_t arrivals_from = arrivals.at.size();

    int64_t ahead = 0, old = 0;
    for (const BadStamp& c : bad_stamps(3'000'000)) {  // servo_history_ms = 2000
        servo_state_t m{};
        m.utime = c.stamp(t);
        m.angle = 0.3;
        nodscan.publish("SERVO_STATE", m);
        ++(c.ahead ? ahead : old);
        steps(20);
        nodscan.publish("LMS_SCAN", scan_at(c.stamp(t)));
        ++(c.ahead ? ahead : old);
        steps(20);
    }
    servo_state_t m{};
    m.utime = std::numeric_limits<int64_t>::max();  // the case that stopped POINTS until restart
    nodscan.publish("SERVO_STATE", m);
    m.utime = t + kYearUs;
    nodscan.publish("SERVO_STATE", m);
    ahead += 2;
    steps(50);
    const int64_t cases_end = t;
    const std::size_t arrivals_cases_end = arrivals.at.size();

    // Every servo sample a year ahead for 3 s: no angles, no POINTS, DEGRADED naming SERVO_STATE.
    servo_good = false;
    bool saw_degraded = false;
    for (int i = 0; i < 300; ++i) {
        ++ahead;
        step();
        saw_degraded = saw_degraded || (nodscan.state() == daemon_status_t::STATE_DEGRADED &&
                                        nodscan.last_error().find("SERVO_STATE") != std::string::npos);
    }
    servo_good = true;
    const int64_t resumed = t0 + k * kStep;
    bool running_again = false;
    for (int i = 0; i < 600 && !running_again; ++i) {
        step();
        running_again = nodscan.state() == daemon_status_t::STATE_RUNNING;
    }
    settle(nodscan, step);
    const int64_t rss_after = rss_kb(nodscan.pid());

    INFO(nodscan.stderr_text());
    CHECK(nodscan.running());
    CHECK(nodscan.counter("stamps_ahead") == ahead);
    CHECK(nodscan.counter("stamps_too_old") == old);
    CHECK(nodscan.counter("servo_rejected") == 0);  // nothing refused reached the history
    // A POINTS cloud for every scan through every case (two periods allow one lost datagram).
    REQUIRE(points_utimes.size() > 50);
    const int64_t step_us = max_step(points_utimes, t0 + 1'000'000, cases_end - 100'000);
    CHECK(step_us <= 2 * kScanPeriod);
    // After the all-refused stretch, the first scan bracketed by good servo samples is output.
    int64_t first_after = 0;
    for (int64_t u : points_utimes)
        if (u >= resumed - 20'000 && first_after == 0) first_after = u;
    CHECK(first_after != 0);
    CHECK(first_after - resumed <= 2 * kScanPeriod);
    const double gap_s = arrivals.max_gap_s(arrivals_from, arrivals_cases_end);
    WARN("ugv-nodscan: largest POINTS step " << step_us << " us of message time, largest arrival gap " << gap_s
                                             << " s; first POINTS " << first_after - resumed
                                             << " us after good servo stamps resumed; RSS " << rss_before << " -> "
                                             << rss_after << " kB");
    CHECK(gap_s < 2.0);  // generous: the daemon batches its input every 50 ms, on a loaded machine
    CHECK(rss_after - rss_before < 4096);
    CHECK(saw_degraded);
    CHECK(running_again);
    CHECK(nodscan.stop() == 0);
}

TEST_CASE("ugv-terrain refuses stamps far from its clock on POSE and POINTS; maps go on and take points again")
{
    // A 40 x 40 map (32 kB, one datagram): a 450 kB one is 7 datagrams of 64 kB, and this
    // test's LCM socket, with the kernel's default buffer, would lose some of them.
    test::LiveDaemon terrain("ugv-terrain", "publish_hz = 5.0\nextent_x_m = 8.0\nextent_y_m = 8.0\n", 7722,
                             "STATUS_TERRAIN");
    std::vector<int64_t> map_utimes;
    terrain.on_decoded<terrain_map_t>("TERRAIN_MAP", [&](const terrain_map_t& m) { map_utimes.push_back(m.utime); });
    REQUIRE(terrain.wait_up(15.0));

    test::SyntheticDrive drive;
    drive.duration_s = 14.0;
    drive.start_utime = (wall_us() / 100'000 + 3) * 100'000;
    const int64_t start = drive.start_utime;
    const std::vector<BadStamp> cases = bad_stamps(3'000'000);  // pose_history_s = 2
    int64_t ahead = 0, old = 0, rss_before = 0, points_fused_degraded = -1;
    bool saw_degraded = false, running_again = false;
    pose_t last_pose{};
    point_cloud_t last_cloud{};
    std::size_t next_case = 0;
    int64_t degraded_from = start + 8'000'000, degraded_to = start + 11'000'000;
    drive.events([&](const std::string& channel, int64_t utime, const std::vector<uint8_t>& bytes) {
        pace_until(terrain, utime);
        if (channel == "POSE") {
            last_pose.decode(bytes.data(), 0, static_cast<int>(bytes.size()));
            terrain.publish_bytes(channel, bytes);
        } else {
            last_cloud.decode(bytes.data(), 0, static_cast<int>(bytes.size()));
            if (utime >= degraded_from && utime < degraded_to) {
                point_cloud_t c = last_cloud;
                c.utime = utime + kYearUs;  // every cloud: DEGRADED naming POINTS.*
                terrain.publish(channel, c);
                ++ahead;
            } else {
                terrain.publish_bytes(channel, bytes);
            }
        }
        if (rss_before == 0 && utime > start + 2'500'000) rss_before = rss_kb(terrain.pid());
        // From 3 s on, a case every 0.8 s: a bad pose, then 0.4 s later a bad cloud.
        if (next_case < 2 * cases.size() + 1 && utime >= start + 3'000'000 + static_cast<int64_t>(next_case) * 400'000) {
            if (next_case == 2 * cases.size()) {  // INT64_MAX then a year ahead, on POSE
                pose_t p = last_pose;
                p.utime = std::numeric_limits<int64_t>::max();
                terrain.publish("POSE", p);
                p.utime = utime + kYearUs;
                terrain.publish("POSE", p);
                ahead += 2;
            } else {
                const BadStamp& c = cases[next_case / 2];
                if (next_case % 2 == 0) {
                    pose_t p = last_pose;
                    p.utime = c.stamp(utime);
                    terrain.publish("POSE", p);
                } else {
                    point_cloud_t cl = last_cloud;
                    cl.utime = c.stamp(utime);
                    terrain.publish("POINTS.front", cl);
                }
                ++(c.ahead ? ahead : old);
            }
            ++next_case;
        }
        if (utime >= degraded_from && utime < degraded_to && terrain.state() == daemon_status_t::STATE_DEGRADED &&
            terrain.last_error().find("POINTS") != std::string::npos) {
            saw_degraded = true;
            points_fused_degraded = terrain.counter("points_fused");
        }
        if (utime >= degraded_to && saw_degraded && terrain.state() == daemon_status_t::STATE_RUNNING) running_again = true;
    });
    settle(terrain, [&] { terrain.pump(0.1); });
    const int64_t rss_after = rss_kb(terrain.pid());

    INFO(terrain.stderr_text());
    CHECK(next_case == 2 * cases.size() + 1);
    CHECK(terrain.running());
    CHECK(terrain.counter("stamps_ahead") == ahead);
    CHECK(terrain.counter("stamps_too_old") == old);
    CHECK(terrain.counter("poses_rejected_out_of_order") == 0);  // nothing refused reached the history
    CHECK(terrain.counter("clouds_rejected_time") == 0);
    // A map every 200 ms of message time through every case and the all-refused stretch
    // (maps go on with the poses); two periods allow one lost on the way to this test.
    REQUIRE(map_utimes.size() > 20);
    const int64_t step_us = max_step(map_utimes, start + 1'000'000, start + 13'500'000);
    CHECK(step_us <= 400'000);
    WARN("ugv-terrain: largest TERRAIN_MAP step " << step_us << " us of message time; " << map_utimes.size()
                                                  << " maps; RSS " << rss_before << " -> " << rss_after << " kB");
    CHECK(rss_after - rss_before < 4096);
    CHECK(saw_degraded);
    CHECK(running_again);
    CHECK(terrain.counter("points_fused") > points_fused_degraded);  // points taken in again
    CHECK(terrain.stop() == 0);
}
