// ugv-imu: MicroStrain 3DM-GX1 -> imu_t on IMU (body FLU -> world ENU). config -> the
// microstrain_gx1 session on a device thread, which publishes; the main thread runs the
// daemon's status and signals. Keys and behaviour: docs/imu.md.
#include "imu_config.hpp"
#include "imu_node.hpp"

int main(int argc, char** argv)
{
    ugv::daemon::Daemon d({.name = "ugv-imu", .status_channel = "STATUS_IMU", .default_config = "/etc/ugv/imu.toml"},
                          argc, argv);
    const ugv::imu_daemon::ImuConfig config = ugv::imu_daemon::read_config(d.config());
    d.start();
    return ugv::imu_daemon::run(d, config);
}
