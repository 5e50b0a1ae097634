// The adapter between the bus and the pose estimator: GPS_FIX, GPS_VEL and IMU in, POSE out
// as the estimator releases poses (on message time only, so a replay is deterministic).
#pragma once

#include "pose_config.hpp"
#include "ugv/daemon/daemon.hpp"

namespace ugv::pose_daemon {

// The daemon: the estimator on the bus until a stop signal, or the end of the --replay log
// (then what is still in the reorder buffer becomes poses too).
int run(daemon::Daemon& d, const PoseConfig& config);

}  // namespace ugv::pose_daemon
