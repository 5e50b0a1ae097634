// ugv-nodscan: LMS_SCAN + SERVO_STATE -> POINTS (3-D points in the body frame with variance).
#include "nodscan_config.hpp"
#include "nodscan_node.hpp"

int main(int argc, char** argv)
{
    ugv::daemon::Daemon d({.name = "ugv-nodscan", .status_channel = "STATUS_NODSCAN", .processing = true,
                           .bus_batch_ms = 50},
                          argc, argv);
    const ugv::nodscan_daemon::NodscanConfig config = ugv::nodscan_daemon::read_config(d.config());
    d.start();
    return ugv::nodscan_daemon::run(d, config);
}
