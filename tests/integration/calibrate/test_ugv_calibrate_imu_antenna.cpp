// ugv-calibrate imu and antenna, the program, on logs written here: IMU and GPS_VEL of a drive
// (stand 5 s, speed up to 2 m/s, straight, a 90 deg left turn of radius 10 m, straight, brake,
// stand) with the IMU mounted 1-2 deg off its configured mounting and the antenna 0.3 m ahead
// and 0.1 m right; and the logs that cannot give them (no motion, no turn, not a log) with
// exit status 2 and one line.
#include <catch2/catch.hpp>

#include <lcm/lcm-cpp.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "ugv/geometry/rotation.hpp"
#include "ugv/gps_velocity_t.hpp"
#include "ugv/imu_t.hpp"
#include "ugv_test/encoded.hpp"
#include "calibrate_run.hpp"
#include "ugv_test/process.hpp"

using namespace ugv;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr int64_t kStart = 1'700'000'000'000'000;
const Eigen::Vector3d kTrueMountDeg(1.0, -1.5, 2.0);
const Eigen::Vector2d kArm(0.3, -0.1);

struct Plan
{
    bool drive = true;
    double turn_deg = 90;
};

void write_log(const std::string& path, const Plan& plan)
{
    lcm::LogFile log(path, "w");
    std::mt19937 rng(7);
    std::normal_distribution<double> g(0.0, 1.0);
    const Eigen::Matrix3d d =
        geometry::rotation_from_euler({kTrueMountDeg.x() * kDeg, kTrueMountDeg.y() * kDeg, kTrueMountDeg.z() * kDeg})
            .transpose();  // configured [0, 0, 0]: the samples are turned by M^T
    double v = 0, heading = 0.4, turned = 0;
    int64_t seq = 0;
    for (int ms = 0; ms < 40'000; ++ms) {
        const double t = ms * 1e-3;
        double a = 0, w = 0;
        if (plan.drive) {
            if (t >= 5 && t < 7) a = 1;  // to 2 m/s
            const bool turning = t >= 12 && turned < plan.turn_deg * kDeg;
            if (turning) w = v / 10.0;
            if (t >= 30 && v > 0) a = -1;
        }
        v = std::max(0.0, v + a * 1e-3);
        heading += w * 1e-3;
        turned += w * 1e-3;
        const int64_t utime = kStart + ms * 1000LL;
        if (ms % 20 == 0) {
            imu_t m{};
            m.utime = utime;
            m.seq = seq++;
            const Eigen::Vector3d f = d * Eigen::Vector3d(a, v * w, 9.80665);
            const Eigen::Vector3d rate = d * Eigen::Vector3d(0, 0, w);
            const Eigen::Quaterniond q(geometry::rotation_from_euler({0, 0, heading}) * d.transpose());
            for (int i = 0; i < 3; ++i) {
                m.acceleration[i] = f[i] + 0.02 * g(rng);
                m.angular_rate[i] = rate[i] + 0.1 * kDeg * g(rng);
            }
            m.orientation[0] = q.w();
            m.orientation[1] = q.x();
            m.orientation[2] = q.y();
            m.orientation[3] = q.z();
            m.valid = static_cast<int32_t>(imu_t::VALID_ORIENTATION) | static_cast<int32_t>(imu_t::VALID_ANGULAR_RATE) |
                      static_cast<int32_t>(imu_t::VALID_ACCELERATION);
            test::write_event(log, utime + 3000, "IMU", m);
        }
        if (ms % 200 == 0) {
            gps_velocity_t gv{};
            gv.utime = utime;
            const Eigen::Vector2d enu = geometry::rotation_2d(heading) * Eigen::Vector2d(v - w * kArm.y(), w * kArm.x());
            gv.horizontal_speed = enu.norm();
            gv.track = geometry::track_from_enu_yaw(std::atan2(enu.y(), enu.x()));
            test::write_event(log, utime + 150'000, "GPS_VEL", gv);
        }
    }
}

using Run = test::CalibrateRun;

Run calibrate(const test::TempDir& dir, const std::vector<std::string>& args) { return test::run_calibrate(dir, args); }

// Exit status 2 with one line on stderr that starts with `start`.
void check_refused(const Run& r, const std::string& start)
{
    INFO(r.err);
    CHECK(r.rc == 2);
    CHECK(r.err.rfind(start, 0) == 0);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(r.out.empty());
}

}  // namespace

TEST_CASE("ugv-calibrate imu and antenna on a drive with a left turn")
{
    test::TempDir dir;
    const std::string log = dir / "drive.lcm";
    write_log(log, {});

    SECTION("imu: the mounting as JSON")
    {
        const Run r = calibrate(dir, {"imu", log, "--json"});
        INFO(r.err << r.out);
        REQUIRE(r.rc == 0);
        CHECK(std::abs(test::json_value(r.out, "roll_deg") - kTrueMountDeg.x()) < 0.05);
        CHECK(std::abs(test::json_value(r.out, "pitch_deg") - kTrueMountDeg.y()) < 0.05);
        CHECK(std::abs(test::json_value(r.out, "yaw_deg") - kTrueMountDeg.z()) < 0.1);
    }
    SECTION("imu: the ready mount_rpy_deg line, from a configured mounting")
    {
        test::write_file(dir / "imu.toml", "device = \"/dev/ugv/imu\"\nmount_rpy_deg = [0, 0, 0]\n");
        const Run r = calibrate(dir, {"imu", log, "--mount-config", dir / "imu.toml"});
        INFO(r.err << r.out);
        REQUIRE(r.rc == 0);
        double roll, pitch, yaw;
        const auto at = r.out.find("\nmount_rpy_deg = [");
        REQUIRE(at != std::string::npos);
        REQUIRE(std::sscanf(r.out.c_str() + at, "\nmount_rpy_deg = [%lf, %lf, %lf]", &roll, &pitch, &yaw) == 3);
        CHECK(std::abs(roll - kTrueMountDeg.x()) < 0.05);
        CHECK(std::abs(yaw - kTrueMountDeg.z()) < 0.1);
    }
    SECTION("antenna: the lever arm and the ready gps_antenna_m line, its height as configured")
    {
        test::write_file(dir / "pose.toml", "gps_antenna_m = [0.0, 0.0, 1.7]\n[datum]\nlat = 50.0\nlon = -110.0\nheight = 700\n");
        const Run r = calibrate(dir, {"antenna", log, "--pose-config", dir / "pose.toml"});
        INFO(r.err << r.out);
        REQUIRE(r.rc == 0);
        CHECK(r.out.find("z      not determined: level driving does not move with it") != std::string::npos);
        double x, y, z;
        const auto at = r.out.find("\ngps_antenna_m = [");
        REQUIRE(at != std::string::npos);
        REQUIRE(std::sscanf(r.out.c_str() + at, "\ngps_antenna_m = [%lf, %lf, %lf]", &x, &y, &z) == 3);
        CHECK(std::abs(x - kArm.x()) < 0.02);
        CHECK(std::abs(y - kArm.y()) < 0.03);
        CHECK(z == 1.7);
    }
}

TEST_CASE("ugv-calibrate imu and antenna refuse a log that cannot give them, in one line")
{
    test::TempDir dir;
    SECTION("standing only")
    {
        write_log(dir / "stand.lcm", {false, 0});
        check_refused(calibrate(dir, {"imu", dir / "stand.lcm"}), "ugv-calibrate: " + dir / "stand.lcm" + ": no motion: ");
        check_refused(calibrate(dir, {"antenna", dir / "stand.lcm"}), "ugv-calibrate: " + dir / "stand.lcm" + ": no motion: ");
    }
    SECTION("no turn")
    {
        write_log(dir / "straight.lcm", {true, 0});
        check_refused(calibrate(dir, {"antenna", dir / "straight.lcm"}), "ugv-calibrate: " + dir / "straight.lcm" + ": no turns: ");
    }
    SECTION("not a log, no IMU")
    {
        test::write_file(dir / "text.lcm", "not a log\n");
        check_refused(calibrate(dir, {"imu", dir / "text.lcm"}), "ugv-calibrate: " + dir / "text.lcm");
        check_refused(calibrate(dir, {"antenna", dir / "text.lcm", "--imu-channel", "NONE"}),
                      "ugv-calibrate: " + dir / "text.lcm");
    }
    SECTION("a config out of range")
    {
        write_log(dir / "drive.lcm", {});
        test::write_file(dir / "imu.toml", "mount_rpy_deg = [0, 0, 500]\n");
        check_refused(calibrate(dir, {"imu", dir / "drive.lcm", "--mount-config", dir / "imu.toml"}),
                      "ugv-calibrate: " + dir / "imu.toml" + ": mount_rpy_deg");
    }
}
