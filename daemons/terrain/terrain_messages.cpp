#include "terrain_messages.hpp"

namespace ugv::terrain_daemon {

terrain::Pose to_pose(const pose_t& msg)
{
    terrain::Pose p;
    p.utime_us = msg.utime;
    p.position_m = {msg.position[0], msg.position[1], msg.position[2]};
    p.orientation = Eigen::Quaterniond(msg.orientation[0], msg.orientation[1], msg.orientation[2], msg.orientation[3]);
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) p.orientation_covariance_rad2(r, c) = msg.orientation_covariance[r * 3 + c];
    return p;
}

bool to_batch(const point_cloud_t& msg, terrain::PointBatch& out)
{
    const auto n = static_cast<std::size_t>(msg.npoints);
    if (msg.npoints < 0 || msg.x.size() != n || msg.y.size() != n || msg.z.size() != n || msg.range.size() != n ||
        msg.variance.size() != n || msg.time_offset.size() != n)
        return false;
    out.utime_us = msg.utime;
    out.count = n;
    out.x_m = msg.x.data();
    out.y_m = msg.y.data();
    out.z_m = msg.z.data();
    out.range_m = msg.range.data();
    out.variance_m2 = msg.variance.data();
    out.time_offset_s = msg.time_offset.data();
    return true;
}

void to_message(const terrain::MapSnapshot& s, const pose_t& pose_msg, int64_t seq, terrain_map_t& msg)
{
    msg.utime = pose_msg.utime;
    msg.seq = seq;
    msg.pose = pose_msg;
    msg.resolution = static_cast<float>(s.resolution_m);
    msg.nx = s.nx;
    msg.ny = s.ny;
    msg.origin_x = static_cast<float>(s.origin_x_m);
    msg.origin_y = static_cast<float>(s.origin_y_m);
    msg.wrap_index = s.wrap_index;
    msg.x_curr = static_cast<float>(s.x_curr_m);
    msg.residual_yaw = static_cast<float>(s.residual_yaw_rad);
    msg.mode = s.mode == terrain::MapMode::world_aligned ? terrain_map_t::MODE_WORLD_ALIGNED : terrain_map_t::MODE_EGOCENTRIC;
    msg.statistics = s.statistics == terrain::StatisticsKind::classical ? terrain_map_t::STATS_CLASSICAL
                                                                        : terrain_map_t::STATS_VARIANCE_WEIGHTED;
    msg.ncells = s.nx * s.ny;
    msg.mean_z = s.mean_z_m;
    msg.variance_z = s.variance_z_m2;
    msg.count = s.count;
    msg.max_z = s.max_z_m;
    msg.min_z = s.min_z_m;
    msg.age_s = s.age_s;
}

}  // namespace ugv::terrain_daemon
