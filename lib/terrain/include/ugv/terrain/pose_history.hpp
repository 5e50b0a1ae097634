// A short history of poses so that each point is transformed with the pose at its own time:
// lib/geometry's pose history (linear position, slerp orientation, linear covariance
// between the two poses around that time).
#pragma once

#include "ugv/geometry/pose_history.hpp"
#include "ugv/terrain/pose.hpp"

namespace ugv::terrain {

using PoseHistory = geometry::PoseHistory;

}  // namespace ugv::terrain
