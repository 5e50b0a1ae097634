// ugv-calibrate laser, the program, on logs written here: nodding scans of flat ground cast
// from a known mount, read back as the tool reads a recording (the mount found from a
// configured one 1.3-1.6 deg and 6 cm off, the [mount] table, the JSON line), and the logs
// it cannot use (no servo, no nodding, a config out of range) with exit status 2 and a reason.
#include <catch2/catch.hpp>

#include <lcm/lcm-cpp.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "ugv/laser_scan_t.hpp"
#include "ugv/nodscan/mount.hpp"
#include "ugv/servo_state_t.hpp"
#include "ugv_test/encoded.hpp"
#include "calibrate_run.hpp"
#include "ugv_test/process.hpp"

using namespace ugv;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr int64_t kStart = 1'700'000'000'000'000;

nodscan::MountGeometry true_mount()
{
    nodscan::MountGeometry m;
    m.axis_xyz_m = {0.2, 0.0, 0.93};
    m.axis_rpy_rad = {-1.3 * kDeg, 1.6 * kDeg, 0.0};
    return m;
}

// The tilt at t: nodding 2-26 deg with a 2 s period (or held at `hold` when given).
double tilt_at(int64_t t_us, double hold)
{
    if (std::isfinite(hold)) return hold;
    const double s = static_cast<double>(t_us - kStart) * 1e-6;
    return (14.0 - 12.0 * std::cos(std::numbers::pi * s)) * kDeg;
}

// `seconds` of SERVO_STATE at 100 Hz and LMS_SCAN at 37.5 Hz (181 beams, 1 deg, beams timed
// linearly over 13.3 ms), the ranges cast onto z = 0 from the true mount at each beam's tilt.
void write_log(const std::string& path, double seconds, bool servo = true, double hold = NAN)
{
    lcm::LogFile log(path, "w");
    std::mt19937 rng(3);
    std::normal_distribution<double> noise(0.0, 0.01);
    const nodscan::MountGeometry m = true_mount();
    const auto end = kStart + static_cast<int64_t>(seconds * 1e6);
    int64_t next_servo = kStart, next_scan = kStart + 5000, seq = 0;
    while (next_servo < end || next_scan < end) {
        if (next_servo <= next_scan) {
            servo_state_t s{};
            s.utime = next_servo;
            s.angle = tilt_at(next_servo, hold);
            s.cia402_state = servo_state_t::STATE_OPERATION_ENABLED;
            if (servo) test::write_event(log, next_servo, "SERVO_STATE", s);
            next_servo += 10'000;
            continue;
        }
        laser_scan_t scan{};
        scan.utime = next_scan;
        scan.seq = seq++;
        scan.sensor_id = "lms";
        scan.angle_min = static_cast<float>(-90 * kDeg);
        scan.angle_increment = static_cast<float>(kDeg);
        scan.time_increment = static_cast<float>(1.0 / 75 / 360);
        scan.scan_period = static_cast<float>(1.0 / 37.5);
        scan.range_max = 80.0f;
        scan.device_scan_counter = -1;
        scan.nranges = 181;
        for (int i = 0; i < 181; ++i) {
            const double a = (i - 90) * kDeg;
            const auto t = next_scan + static_cast<int64_t>(std::llround(i * static_cast<double>(scan.time_increment) * 1e6));
            const double tilt = tilt_at(t, hold);
            const Eigen::Vector3d o = nodscan::laser_origin_body(m, tilt);
            const Eigen::Vector3d d = nodscan::beam_point_body(m, tilt, a, 1.0) - o;
            const double r = d.z() < -1e-6 ? -o.z() / d.z() + noise(rng) : NAN;
            scan.ranges.push_back(std::isfinite(r) && r < 80 ? static_cast<float>(r) : NAN);
            scan.flags.push_back(std::isfinite(scan.ranges.back()) ? laser_scan_t::FLAG_OK : laser_scan_t::FLAG_OVERFLOW);
        }
        test::write_event(log, next_scan + 14'000, "LMS_SCAN", scan);
        next_scan += 26'667;
    }
}

using Run = test::CalibrateRun;

Run calibrate(const test::TempDir& dir, std::vector<std::string> args)
{
    args.insert(args.begin(), "laser");
    return test::run_calibrate(dir, args);
}

}  // namespace

TEST_CASE("ugv-calibrate laser finds the mount of a nodding laser over flat ground")
{
    test::TempDir dir;
    write_log(dir / "lot.lcm", 20.0);
    test::write_file(dir / "nodscan.toml", "channel = \"POINTS\"\n[mount]\ntilt_axis_xyz_m = [0.2, 0.0, 0.87]\n");

    SECTION("as JSON")
    {
        const Run r = calibrate(dir, {dir / "lot.lcm", "--mount-config", dir / "nodscan.toml", "--json"});
        INFO(r.err);
        INFO(r.out);
        REQUIRE(r.rc == 0);
        CHECK(std::abs(test::json_value(r.out, "roll_deg") - -1.3) < 0.05);
        CHECK(std::abs(test::json_value(r.out, "pitch_deg") - 1.6) < 0.05);
        CHECK(std::abs(test::json_value(r.out, "height_m") - 0.93) < 0.005);
        CHECK(r.out.find("\"yaw_deg\": {\"value\": 0.00000, \"sigma\": null, \"initial\": 0.00000, \"determined\": false}") !=
              std::string::npos);
    }
    SECTION("as text with a ready [mount] table")
    {
        const Run r = calibrate(dir, {dir / "lot.lcm", "--mount-config", dir / "nodscan.toml"});
        INFO(r.err);
        INFO(r.out);
        REQUIRE(r.rc == 0);
        CHECK(r.out.find("yaw     not determined: flat ground does not move with it") != std::string::npos);
        const auto table = r.out.find("\n[mount]\ntilt_axis_xyz_m = [");
        REQUIRE(table != std::string::npos);
        double x, y, z, roll, pitch, yaw;
        REQUIRE(std::sscanf(r.out.c_str() + table, "\n[mount]\ntilt_axis_xyz_m = [%lf, %lf, %lf]\ntilt_axis_rpy_deg = [%lf, %lf, %lf]",
                            &x, &y, &z, &roll, &pitch, &yaw) == 6);
        CHECK((x == 0.2 && y == 0.0 && yaw == 0.0));
        CHECK(std::abs(z - 0.93) < 0.005);
        CHECK(std::abs(roll - -1.3) < 0.05);
        CHECK(std::abs(pitch - 1.6) < 0.05);
    }
}

TEST_CASE("ugv-calibrate laser says why a log cannot give the mount, with exit status 2")
{
    test::TempDir dir;
    SECTION("no servo")
    {
        write_log(dir / "a.lcm", 3.0, false);
        const Run r = calibrate(dir, {dir / "a.lcm"});
        CHECK(r.rc == 2);
        CHECK(r.err.find("no laser_scan_t on LMS_SCAN with servo_state_t on SERVO_STATE") != std::string::npos);
    }
    SECTION("no nodding")
    {
        write_log(dir / "b.lcm", 5.0, true, 12 * kDeg);
        const Run r = calibrate(dir, {dir / "b.lcm"});
        CHECK(r.rc == 2);
        CHECK(r.err.find("the laser did not nod: tilt span 0.0 deg") != std::string::npos);
    }
    SECTION("too short")
    {
        write_log(dir / "c.lcm", 0.3);
        const Run r = calibrate(dir, {dir / "c.lcm"});
        CHECK(r.rc == 2);
        CHECK(r.err.find("too few beams between 2.0 and 12.0 m") != std::string::npos);
    }
    SECTION("a mount out of range in the config")
    {
        write_log(dir / "d.lcm", 0.3);
        test::write_file(dir / "bad.toml", "[mount]\ntilt_axis_rpy_deg = [0, 0, 400]\n");
        const Run r = calibrate(dir, {dir / "d.lcm", "--mount-config", dir / "bad.toml"});
        CHECK(r.rc == 2);
        CHECK(r.err.find("tilt_axis_rpy_deg") != std::string::npos);
    }
    SECTION("not a log")
    {
        test::write_file(dir / "e.lcm", "hello");
        const Run r = calibrate(dir, {dir / "e.lcm"});
        CHECK(r.rc == 2);
        CHECK(!r.err.empty());
    }
}
