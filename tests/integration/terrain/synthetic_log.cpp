#include "synthetic_log.hpp"

#include <lcm/lcm-cpp.hpp>

#include <cmath>
#include <vector>

#include <ugv/point_cloud_t.hpp>
#include <ugv/pose_t.hpp>

namespace ugv::test {

double SyntheticDrive::height_at(double x, double y) const
{
    const bool in_box = x >= box_min.x() && x <= box_max.x() && y >= box_min.y() && y <= box_max.y();
    return in_box ? box_height_m : 0.0;
}

Eigen::Vector3d SyntheticDrive::pose_at(double t) const
{
    const double speed = 1.0, turn_rate = turn_rate_rad_s, turn_start = 3.0;
    if (t < turn_start) return {speed * t, 0.0, 0.0};
    const double yaw = turn_rate * (t - turn_start);
    return {turn_start + speed * std::sin(yaw) / turn_rate, speed * (1.0 - std::cos(yaw)) / turn_rate, yaw};
}

namespace {

std::vector<uint8_t> encoded(const auto& msg)
{
    std::vector<uint8_t> buf(static_cast<std::size_t>(msg.getEncodedSize()));
    msg.encode(buf.data(), 0, static_cast<int>(buf.size()));
    return buf;
}

}  // namespace

void SyntheticDrive::write_log(const std::string& path) const
{
    lcm::LogFile log(path, "w");
    events([&log](const std::string& channel, int64_t utime, const std::vector<uint8_t>& bytes) {
        lcm::LogEvent ev{};
        ev.timestamp = utime;
        ev.channel = channel;
        ev.datalen = static_cast<int32_t>(bytes.size());
        ev.data = const_cast<uint8_t*>(bytes.data());
        log.writeEvent(&ev);
    });
}

void SyntheticDrive::events(const std::function<void(const std::string&, int64_t, const std::vector<uint8_t>&)>& out) const
{
    const int64_t pose_period_us = 100'000;
    const int64_t cloud_step_us = cloud_period_us / static_cast<int64_t>(lasers.size());  // lasers in turn
    int64_t pose_seq = 0, cloud_seq = 0;
    int64_t next_pose = 0, next_cloud = 20'000;
    const int64_t end = static_cast<int64_t>(duration_s * 1e6);
    while (next_pose <= end || next_cloud <= end) {
        if (next_pose <= next_cloud) {
            const Eigen::Vector3d p = pose_at(static_cast<double>(next_pose) * 1e-6);
            pose_t m{};
            m.utime = start_utime + next_pose;
            m.seq = pose_seq++;
            m.position[0] = p.x();
            m.position[1] = p.y();
            m.orientation[0] = std::cos(p.z() / 2);
            m.orientation[3] = std::sin(p.z() / 2);
            m.yaw = p.z();
            const double var = orientation_sigma_rad * orientation_sigma_rad;
            m.orientation_covariance[0] = m.orientation_covariance[4] = m.orientation_covariance[8] = var;
            m.status = pose_t::STATUS_OK;
            out("POSE", m.utime, encoded(m));
            next_pose += pose_period_us;
        } else {
            // One line across the ground at a distance that nods from 2 to 14 m.
            const std::string& laser = lasers[static_cast<std::size_t>(cloud_seq) % lasers.size()];
            const double distance = 2.0 + 0.4 * static_cast<double>(cloud_seq % 31);
            point_cloud_t m{};
            m.utime = start_utime + next_cloud;
            m.seq = cloud_seq++;
            m.sensor_id = laser;
            m.sensor_origin[0] = 0.5;
            m.sensor_origin[2] = 0.87;
            const int n = points_per_cloud;
            const double spacing_m = 12.0 / (n - 1);  // exactly 0.1 for the default 121 points
            for (int k = 0; k < n; ++k) {
                const double offset = 0.02 * k / (n - 1);
                const Eigen::Vector3d pose = pose_at(static_cast<double>(next_cloud) * 1e-6 + offset);
                const double c = std::cos(pose.z()), s = std::sin(pose.z());
                const double bx = distance, by = -6.0 + spacing_m * k;
                const double wx = pose.x() + c * bx - s * by, wy = pose.y() + s * bx + c * by;
                const double bz = height_at(wx, wy);
                m.x.push_back(static_cast<float>(bx));
                m.y.push_back(static_cast<float>(by));
                m.z.push_back(static_cast<float>(bz));
                const Eigen::Vector3d ray(bx - 0.5, by, bz - 0.87);
                m.range.push_back(static_cast<float>(ray.norm()));
                m.variance.push_back(1e-4f);
                m.time_offset.push_back(static_cast<float>(offset));
            }
            m.npoints = n;
            out("POINTS." + laser, m.utime, encoded(m));
            next_cloud += cloud_step_us;
        }
    }
}

}  // namespace ugv::test
