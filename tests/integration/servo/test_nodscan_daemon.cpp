// ugv-nodscan on a synthetic log (--replay): a laser 0.9 m up nodding over flat ground. Every
// assembled point must lie on the ground (z = 0), which holds only if each beam used the
// servo angle at its own time; NaN beams are dropped and counted.
#include <catch2/catch.hpp>

#include <lcm/lcm-cpp.hpp>

#include <cmath>
#include <numbers>
#include <vector>

#include "ugv/laser_scan_t.hpp"
#include "ugv/point_cloud_t.hpp"
#include "ugv/servo_state_t.hpp"
#include "ugv_test/encoded.hpp"
#include "ugv_test/process.hpp"

using namespace ugv;

namespace {

constexpr double kHeight = 0.9;
constexpr int64_t kStart = 1'700'000'000'000'000;

double tilt_at(double t) { return 0.35 + 0.12 * std::sin(2 * std::numbers::pi * 0.5 * t); }

// 3 s of servo states at 100 Hz and scans at 37.5 Hz (181 beams over 180 deg, 13.3 ms).
int write_log(const std::string& path)
{
    lcm::LogFile log(path, "w");
    const int64_t servo_period = 10'000, scan_period = 26'667, beam_span = 13'333;
    int64_t next_servo = 0, next_scan = 5'000, servo_seq = 0, scan_seq = 0;
    int nan_beams = 0;
    while (next_servo <= 3'000'000) {
        // A scan is published when its last beam has been measured.
        if (next_scan + beam_span <= next_servo) {
            laser_scan_t s{};
            s.utime = kStart + next_scan;
            s.seq = scan_seq++;
            s.sensor_id = "front";
            s.angle_min = static_cast<float>(-std::numbers::pi / 2);
            s.angle_increment = static_cast<float>(std::numbers::pi / 180);
            s.time_increment = static_cast<float>(beam_span * 1e-6 / 180);
            s.scan_period = static_cast<float>(scan_period * 1e-6);
            s.range_max = 81.0f;
            s.device_scan_counter = static_cast<int32_t>(s.seq);
            s.nranges = 181;
            for (int i = 0; i < 181; ++i) {
                const double a = static_cast<double>(s.angle_min) + static_cast<double>(s.angle_increment) * i;
                const double t = static_cast<double>(next_scan) * 1e-6 + static_cast<double>(s.time_increment) * i;
                const double c = std::cos(a);
                const bool hit = c > 0.25;
                s.ranges.push_back(hit ? static_cast<float>(kHeight / (std::sin(tilt_at(t)) * c)) : NAN);
                s.flags.push_back(hit ? laser_scan_t::FLAG_OK : laser_scan_t::FLAG_OVERFLOW);
                nan_beams += hit ? 0 : 1;
            }
            test::write_event(log, s.utime + beam_span, "LMS_SCAN", s);
            next_scan += scan_period;
            continue;
        }
        servo_state_t m{};
        m.utime = kStart + next_servo;
        m.seq = servo_seq++;
        m.angle = tilt_at(static_cast<double>(next_servo) * 1e-6);
        m.cia402_state = servo_state_t::STATE_OPERATION_ENABLED;
        test::write_event(log, m.utime, "SERVO_STATE", m);
        next_servo += servo_period;
    }
    return nan_beams;
}

}  // namespace

TEST_CASE("ugv-nodscan --replay puts every beam of a nodding laser on flat ground")
{
    test::TempDir dir;
    write_log(dir / "in.log");
    test::write_file(dir / "nodscan.toml",
                     "range_sigma_m = 0.01\nangle_sigma_deg = 0.1\n[mount]\ntilt_axis_xyz_m = [0.4, 0.0, 0.9]\n");
    const int rc = test::run({test::bin("ugv-nodscan"), "--config", dir / "nodscan.toml", "--replay", dir / "in.log",
                              "--out", dir / "out.log"},
                             dir / "out", dir / "err", 60.0);
    INFO(test::read_file(dir / "err"));
    REQUIRE(rc == 0);

    lcm::LogFile out(dir / "out.log", "r");
    int clouds = 0;
    std::size_t points = 0;
    double worst_z = 0.0;
    int64_t last_seq = -1;
    for (const lcm::LogEvent* ev = out.readNextEvent(); ev; ev = out.readNextEvent()) {
        if (ev->channel != "POINTS") continue;
        point_cloud_t pc;
        REQUIRE(pc.decode(ev->data, 0, ev->datalen) == ev->datalen);
        CHECK(pc.seq == last_seq + 1);
        last_seq = pc.seq;
        CHECK(pc.sensor_id == "front");
        CHECK(pc.sensor_origin[2] == Approx(kHeight));
        REQUIRE(pc.npoints > 0);
        for (int i = 0; i < pc.npoints; ++i) {
            const auto k = static_cast<std::size_t>(i);
            worst_z = std::max(worst_z, std::fabs(static_cast<double>(pc.z[k])));
            REQUIRE(pc.x[k] > 0.4f);
            // Sensor variance: range noise plus angle noise times range.
            const double r = pc.range[k];
            const double sigma_a = 0.1 * std::numbers::pi / 180;
            REQUIRE(pc.variance[k] == Approx(1e-4 + r * r * sigma_a * sigma_a).epsilon(1e-4));
        }
        points += static_cast<std::size_t>(pc.npoints);
        ++clouds;
    }
    // 3 s at 37.5 Hz, less the last scan or two still waiting when the log ended.
    CHECK(clouds >= 108);
    CHECK(worst_z < 0.003);
    // Beams with cos(angle) <= 0.25 (beyond +-75.5 deg) had NaN ranges: 151 of 181 are valid.
    CHECK(points == static_cast<std::size_t>(clouds) * 151);
}
