#include "imu_messages.hpp"

#include <limits>

namespace ugv::imu_daemon {

ugv::imu_t to_message(const microstrain_gx1::Sample& s, int64_t seq, float orientation_sigma_rad)
{
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    ugv::imu_t m{};
    m.utime = s.utime;
    m.seq = seq;
    m.device_ticks = s.device_ticks;
    m.valid = 0;
    const auto& b = s.body;
    if (b.has_orientation) {
        const auto& q = b.attitude.q_enu_body;
        m.orientation[0] = q.w();
        m.orientation[1] = q.x();
        m.orientation[2] = q.y();
        m.orientation[3] = q.z();
        m.roll = b.attitude.roll_rad;
        m.pitch = b.attitude.pitch_rad;
        m.yaw = b.attitude.yaw_rad;
        m.orientation_sigma = orientation_sigma_rad;
        m.valid |= int32_t{ugv::imu_t::VALID_ORIENTATION} | int32_t{ugv::imu_t::VALID_EULER};
    } else {
        for (double& v : m.orientation) v = nan;
        m.roll = m.pitch = m.yaw = nan;
        m.orientation_sigma = std::numeric_limits<float>::quiet_NaN();
    }
    auto put = [&](const Eigen::Vector3d& v, bool has, double (&out)[3], int32_t bit) {
        for (int i = 0; i < 3; ++i) out[i] = has ? v[i] : nan;
        if (has) m.valid |= bit;
    };
    put(b.rate_radps, b.has_rate, m.angular_rate, ugv::imu_t::VALID_ANGULAR_RATE);
    put(b.accel_mps2, b.has_accel, m.acceleration, ugv::imu_t::VALID_ACCELERATION);
    put(b.mag_gauss, b.has_mag, m.magnetic_field, ugv::imu_t::VALID_MAGNETIC_FIELD);
    return m;
}

}  // namespace ugv::imu_daemon
