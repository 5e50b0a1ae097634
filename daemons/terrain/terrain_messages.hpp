// pose_t / point_cloud_t / terrain_map_t <-> the terrain library's types.
#pragma once

#include <ugv/point_cloud_t.hpp>
#include <ugv/pose_t.hpp>
#include <ugv/terrain_map_t.hpp>

#include "ugv/terrain/terrain_mapper.hpp"

namespace ugv::terrain_daemon {

terrain::Pose to_pose(const pose_t& msg);
// A view of the message's arrays; false when the arrays are inconsistent with npoints.
bool to_batch(const point_cloud_t& msg, terrain::PointBatch& out);
// Fills msg from the snapshot (pose_msg: the message of the pose the map refers to).
void to_message(const terrain::MapSnapshot& snapshot, const pose_t& pose_msg, int64_t seq, terrain_map_t& msg);

}  // namespace ugv::terrain_daemon
