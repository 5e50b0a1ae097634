#include "pose_messages.hpp"

#include <algorithm>

namespace ugv::pose_daemon {

estimation::GpsFix to_fix(const gps_fix_t& m)
{
    estimation::GpsFix f;
    f.utime = m.utime;
    f.latitude_deg = m.latitude;
    f.longitude_deg = m.longitude;
    f.height_m = m.height;
    f.sigma_north_m = m.sigma_latitude;
    f.sigma_east_m = m.sigma_longitude;
    f.sigma_up_m = m.sigma_height;
    // Values outside the enum (a newer driver) are treated as unknown, i.e. unusable.
    f.quality = (m.fix_quality >= 0 && m.fix_quality <= gps_fix_t::QUALITY_UNKNOWN)
                    ? static_cast<estimation::FixQuality>(m.fix_quality)
                    : estimation::FixQuality::unknown;
    return f;
}

estimation::GpsVelocity to_velocity(const gps_velocity_t& m)
{
    estimation::GpsVelocity v;
    v.utime = m.utime;
    v.horizontal_speed_mps = m.horizontal_speed;
    v.track_rad = m.track;
    v.vertical_speed_mps = m.vertical_speed;
    return v;
}

estimation::ImuSample to_imu(const imu_t& m)
{
    estimation::ImuSample s;
    s.utime = m.utime;
    s.has_orientation = (m.valid & imu_t::VALID_ORIENTATION) != 0;
    s.orientation = Eigen::Quaterniond(m.orientation[0], m.orientation[1], m.orientation[2], m.orientation[3]);
    s.has_rate = (m.valid & imu_t::VALID_ANGULAR_RATE) != 0;
    s.rate_rps = Eigen::Vector3d(m.angular_rate[0], m.angular_rate[1], m.angular_rate[2]);
    s.has_accel = (m.valid & imu_t::VALID_ACCELERATION) != 0;
    s.accel_mps2 = Eigen::Vector3d(m.acceleration[0], m.acceleration[1], m.acceleration[2]);
    s.orientation_sigma_rad = m.orientation_sigma;
    return s;
}

namespace {

void copy3x3(const Eigen::Matrix3d& m, double (&out)[9])
{
    for (int r = 0; r < 3; ++r) {
        for (int c = 0; c < 3; ++c) {
            out[3 * r + c] = m(r, c);
        }
    }
}

int8_t status_of(estimation::PoseStatus s)
{
    switch (s) {
    case estimation::PoseStatus::ok: return pose_t::STATUS_OK;
    case estimation::PoseStatus::degraded: return pose_t::STATUS_DEGRADED;
    case estimation::PoseStatus::fault: return pose_t::STATUS_FAULT;
    case estimation::PoseStatus::initializing: return pose_t::STATUS_INITIALIZING;
    }
    return pose_t::STATUS_FAULT;
}

}  // namespace

pose_t to_message(const estimation::PoseEstimate& p, int64_t seq)
{
    pose_t m{};
    m.utime = p.utime;
    m.seq = seq;
    for (int i = 0; i < 3; ++i) {
        m.position[i] = p.position(i);
        m.velocity[i] = p.velocity(i);
        m.rotation_rate[i] = p.rotation_rate(i);
    }
    m.orientation[0] = p.orientation.w();
    m.orientation[1] = p.orientation.x();
    m.orientation[2] = p.orientation.y();
    m.orientation[3] = p.orientation.z();
    m.roll = p.roll;
    m.pitch = p.pitch;
    m.yaw = p.yaw;
    copy3x3(p.position_covariance, m.position_covariance);
    copy3x3(p.velocity_covariance, m.velocity_covariance);
    copy3x3(p.orientation_covariance, m.orientation_covariance);
    m.datum_latitude = p.datum.latitude_deg;
    m.datum_longitude = p.datum.longitude_deg;
    m.datum_height = p.datum.height_m;
    m.status = status_of(p.status);
    return m;
}

}  // namespace ugv::pose_daemon
