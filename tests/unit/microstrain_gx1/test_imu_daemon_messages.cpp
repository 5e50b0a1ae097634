// ugv-imu's conversion (daemons/imu/imu_messages.cpp): valid bits and NaN for what the
// sample does not carry, quaternion order w, x, y, z.
#include <catch2/catch.hpp>

#include <cmath>

#include "imu_messages.hpp"

using namespace ugv;

TEST_CASE("imu message: a rate-only sample has NaN orientation, its rate, and only the rate's valid bit")
{
    microstrain_gx1::Sample s;
    s.utime = 1000;
    s.device_ticks = 77;
    s.body.has_rate = true;
    s.body.rate_radps = Eigen::Vector3d(0.1, -0.2, 0.3);
    const imu_t m = imu_daemon::to_message(s, 5, 0.01f);
    CHECK(m.utime == 1000);
    CHECK(m.seq == 5);
    CHECK(m.device_ticks == 77);
    CHECK(m.valid == imu_t::VALID_ANGULAR_RATE);
    CHECK(std::isnan(m.orientation[0]));
    CHECK(std::isnan(m.yaw));
    CHECK(std::isnan(m.orientation_sigma));
    CHECK(m.angular_rate[1] == -0.2);
    CHECK(std::isnan(m.acceleration[0]));
}

TEST_CASE("imu message: an orientation sample carries the quaternion as w, x, y, z and its sigma")
{
    microstrain_gx1::Sample s;
    s.body.has_orientation = true;
    s.body.attitude = microstrain_gx1::attitude_from_rotation(
        Eigen::AngleAxisd(0.4, Eigen::Vector3d::UnitZ()).toRotationMatrix());
    const imu_t m = imu_daemon::to_message(s, 0, 0.02f);
    CHECK((m.valid & imu_t::VALID_ORIENTATION) != 0);
    CHECK((m.valid & imu_t::VALID_EULER) != 0);
    CHECK(m.orientation[0] == Approx(std::cos(0.2)));
    CHECK(std::abs(m.orientation[3]) == Approx(std::sin(0.2)));
    CHECK(m.yaw == Approx(0.4));
    CHECK(m.orientation_sigma == 0.02f);
}
