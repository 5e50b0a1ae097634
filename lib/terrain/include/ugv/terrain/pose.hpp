// The vehicle pose the map needs (position, orientation, and the roll/pitch/yaw covariance
// that gives the orientation error of eq. 19) is lib/geometry's stamped pose.
#pragma once

#include "ugv/geometry/pose.hpp"

namespace ugv::terrain {

using Pose = geometry::StampedPose;

}  // namespace ugv::terrain
