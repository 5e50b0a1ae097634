// ugv-pose's conversions (daemons/pose/pose_messages.cpp): what the estimator is given and
// what it publishes, field by field.
#include <catch2/catch.hpp>

#include <cmath>

#include "pose_messages.hpp"

using namespace ugv;

TEST_CASE("pose messages: a fix's quality outside the enum is unknown; sigmas map north/east/up")
{
    gps_fix_t m{};
    m.utime = 1'700'000'000'000'000;
    m.latitude = 50.25;
    m.longitude = -110.5;
    m.height = 760.0;
    m.sigma_latitude = 0.25f;
    m.sigma_longitude = 0.5f;
    m.sigma_height = 0.75f;
    m.fix_quality = gps_fix_t::QUALITY_UNKNOWN + 5;
    const estimation::GpsFix f = pose_daemon::to_fix(m);
    CHECK(f.utime == m.utime);
    CHECK(f.latitude_deg == 50.25);
    CHECK(f.longitude_deg == -110.5);
    CHECK(f.sigma_north_m == 0.25);
    CHECK(f.sigma_east_m == 0.5);
    CHECK(f.sigma_up_m == 0.75);
    CHECK(f.quality == estimation::FixQuality::unknown);
    m.fix_quality = -1;
    CHECK(pose_daemon::to_fix(m).quality == estimation::FixQuality::unknown);
}

TEST_CASE("pose messages: an IMU sample's valid bits decide what the estimator uses")
{
    imu_t m{};
    m.utime = 42;
    m.valid = imu_t::VALID_ANGULAR_RATE;
    m.orientation[0] = 1.0;
    m.angular_rate[2] = 0.25;
    const estimation::ImuSample s = pose_daemon::to_imu(m);
    CHECK_FALSE(s.has_orientation);
    CHECK(s.has_rate);
    CHECK_FALSE(s.has_accel);
    CHECK(s.rate_rps.z() == 0.25);
}

TEST_CASE("pose messages: an estimate becomes pose_t with w,x,y,z order, row-major covariances and status")
{
    estimation::PoseEstimate p;
    p.utime = 7;
    p.position = Eigen::Vector3d(1, 2, 3);
    p.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()));
    p.position_covariance << 1, 2, 3, 4, 5, 6, 7, 8, 9;
    p.status = estimation::PoseStatus::degraded;
    const pose_t m = pose_daemon::to_message(p, 11);
    CHECK(m.utime == 7);
    CHECK(m.seq == 11);
    CHECK(m.position[2] == 3.0);
    CHECK(m.orientation[0] == Approx(std::cos(0.25)));
    CHECK(m.orientation[3] == Approx(std::sin(0.25)));
    CHECK(m.position_covariance[1] == 2.0);
    CHECK(m.position_covariance[3] == 4.0);
    CHECK(m.status == pose_t::STATUS_DEGRADED);
}
