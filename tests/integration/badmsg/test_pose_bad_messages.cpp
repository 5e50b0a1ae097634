// ugv-pose live on LCM (port 7960) fed a stationary vehicle (IMU 50 Hz, GPS fix and velocity
// 5 Hz, data time at ~2x real time) with every bad message of issue 11 mixed in. The daemon
// must keep running, every POSE must stay finite and at the vehicle (the 50 m jump must not
// move it), and each case must show in its STATUS_POSE counter.
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <limits>

#include <ugv/gps_fix_t.hpp>
#include <ugv/gps_velocity_t.hpp>
#include <ugv/imu_t.hpp>
#include <ugv/pose_t.hpp>

#include "live_daemon.hpp"

using namespace ugv;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int64_t kStepUs = 20'000;  // one IMU sample per step; a fix and a velocity every 10
constexpr double kLat = 50.27, kLon = -110.74, kHeight = 750.0;
constexpr double kMetresPerDegLat = 111'250.0;  // at 50 deg, to within 0.1 %

gps_fix_t fix_at(int64_t utime, double north_m = 0.0)
{
    gps_fix_t f{};
    f.utime = utime;
    f.latitude = kLat + north_m / kMetresPerDegLat;
    f.longitude = kLon;
    f.height = kHeight;
    f.sigma_latitude = f.sigma_longitude = 0.5f;
    f.sigma_height = 1.0f;
    f.fix_quality = gps_fix_t::QUALITY_DGPS;
    f.satellites_used = 9;
    f.differential_age = 2.0f;
    return f;
}

gps_velocity_t velocity_at(int64_t utime)
{
    gps_velocity_t v{};
    v.utime = utime;
    v.vertical_speed = 0.0;
    return v;
}

imu_t imu_at(int64_t utime)
{
    imu_t m{};
    m.utime = utime;
    m.orientation[0] = 1.0;
    m.acceleration[2] = 9.80665;
    m.orientation_sigma = 0.01f;
    m.valid = int32_t{imu_t::VALID_ORIENTATION} | int32_t{imu_t::VALID_ANGULAR_RATE} | int32_t{imu_t::VALID_ACCELERATION};
    return m;
}

bool all_finite(const double* v, int n)
{
    for (int i = 0; i < n; ++i) {
        if (!std::isfinite(v[i])) return false;
    }
    return true;
}

}  // namespace

TEST_CASE("ugv-pose: bad messages on GPS_FIX, GPS_VEL and IMU are dropped and counted; POSE stays finite and in place")
{
    // Data time runs at ~2x real time from now: the stamp bounds (test_bad_stamps) are
    // widened so that only the cases below are refused.
    test::LiveDaemon pose("ugv-pose", "max_stamp_ahead_s = 60.0\nmax_stamp_age_s = 60.0\n", 7960, "STATUS_POSE");
    const int64_t kStartUtime = std::chrono::duration_cast<std::chrono::microseconds>(
                                    std::chrono::system_clock::now().time_since_epoch())
                                    .count() /
                                1'000'000 * 1'000'000;
    int poses = 0, bad_poses = 0;
    double max_offset_m = 0.0;
    pose.on_decoded<pose_t>("POSE", [&](const pose_t& p) {
        ++poses;
        const bool finite = all_finite(p.position, 3) && all_finite(p.velocity, 3) && all_finite(p.orientation, 4) &&
                            all_finite(p.position_covariance, 9) && all_finite(p.velocity_covariance, 9) &&
                            all_finite(p.orientation_covariance, 9);
        if (!finite) ++bad_poses;
        else max_offset_m = std::max(max_offset_m, std::hypot(p.position[0], p.position[1]));
    });
    REQUIRE(pose.wait_up(15.0));

    // The good stream, step by step; `bad` runs after step k's good messages.
    const auto run = [&](int first, int last, const std::function<void(int, int64_t)>& bad) {
        for (int k = first; k < last; ++k) {
            const int64_t t = kStartUtime + k * kStepUs;
            pose.publish("IMU", imu_at(t));
            if (k % 10 == 0) {
                pose.publish("GPS_FIX", fix_at(t));
                pose.publish("GPS_VEL", velocity_at(t));
            }
            if (bad) bad(k, t);
            pose.pump(0.010);
        }
    };
    run(0, 200, {});
    const int poses_before_cases = poses;

    int non_finite_cases = 0, too_old_cases = 0;  // utime 0 is refused by its stamp first
    run(200, 400, [&](int k, int64_t t) {
        auto fix = fix_at(t + 5'000);
        auto vel = velocity_at(t + 5'000);
        auto imu = imu_at(t + 5'000);
        switch (k) {
        case 210: fix.latitude = kNaN; pose.publish("GPS_FIX", fix); ++non_finite_cases; break;
        case 215: fix.height = kInf; pose.publish("GPS_FIX", fix); ++non_finite_cases; break;
        case 220: fix.latitude = 91.0; pose.publish("GPS_FIX", fix); ++non_finite_cases; break;
        case 225: fix.utime = 0; pose.publish("GPS_FIX", fix); ++too_old_cases; break;
        case 230: fix.sigma_latitude = -1.0f; pose.publish("GPS_FIX", fix); ++non_finite_cases; break;
        case 235: imu.orientation[2] = kNaN; pose.publish("IMU", imu); ++non_finite_cases; break;
        case 240: imu.orientation[0] = 2.0; pose.publish("IMU", imu); ++non_finite_cases; break;
        case 245: imu.acceleration[0] = kInf; pose.publish("IMU", imu); ++non_finite_cases; break;
        case 250: vel.horizontal_speed = kInf; pose.publish("GPS_VEL", vel); ++non_finite_cases; break;
        case 255: vel.track = kNaN; pose.publish("GPS_VEL", vel); ++non_finite_cases; break;
        // A 50 m multipath jump: well formed, so only the gate can refuse it.
        case 300: pose.publish("GPS_FIX", fix_at(t + 5'000, 50.0)); break;
        // Time going backwards: a fix 3 s older than what the filter has applied.
        case 320: pose.publish("GPS_FIX", fix_at(t - 3'000'000)); break;
        // Out of order within the reorder window: the next two IMU samples, the later first.
        case 340:
            pose.publish("IMU", imu_at(t + 15'000));
            pose.publish("IMU", imu_at(t + 10'000));
            break;
        // A duplicate: the same fix twice (as a re-sent or looped-back message arrives).
        case 360: pose.publish("GPS_FIX", fix_at(t)); break;
        // Truncated and random bytes on the input channels.
        case 370: {
            auto bytes = test::encoded(fix_at(t));
            bytes.resize(bytes.size() / 2);
            pose.publish_bytes("GPS_FIX", bytes);
            pose.publish_bytes("IMU", {0xde, 0xad, 0xbe, 0xef, 0x01, 0x02, 0x03});
            pose.publish_bytes("GPS_VEL", std::vector<uint8_t>(300, 0x5a));
            break;
        }
        default: break;
        }
    });
    // Good data until a status taken after every case has arrived (1 Hz).
    const int statuses_after_cases = pose.statuses();
    int k = 400;
    while (pose.statuses() < statuses_after_cases + 2 && k < 900) {
        run(k, k + 10, {});
        k += 10;
    }

    INFO(pose.stderr_text());
    CHECK(pose.running());
    CHECK(poses > poses_before_cases);
    CHECK(bad_poses == 0);
    CHECK(max_offset_m < 1.0);  // the 50 m jump never reached the pose
    CHECK(pose.counter("non_finite") == non_finite_cases);
    CHECK(pose.counter("stamps_too_old") == too_old_cases);
    CHECK(pose.counter("gps_rejected") == 1);
    CHECK(pose.counter("late") >= 1);
    CHECK(pose.counter("reordered") >= 1);
    CHECK(pose.counter("duplicates") == 1);
    CHECK(pose.counter("bus_decode_failures") == 3);
    CHECK(pose.stop() == 0);
}
