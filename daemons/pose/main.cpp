// ugv-pose: GPS_FIX + GPS_VEL + IMU -> POSE, a 6-DOF pose with covariance in local ENU right
// after each IMU sample (docs/pose.md). Driven by message utime only, so --replay LOG --out
// LOG is deterministic.
#include "pose_config.hpp"
#include "pose_node.hpp"

int main(int argc, char** argv)
{
    ugv::daemon::Daemon d({.name = "ugv-pose", .status_channel = "STATUS_POSE", .processing = true,
                           .bus_batch_ms = 0},  // a batch would hold each POSE back by up to its length
                          argc, argv);
    const ugv::pose_daemon::PoseConfig config = ugv::pose_daemon::read_config(d.config());
    d.start();
    return ugv::pose_daemon::run(d, config);
}
