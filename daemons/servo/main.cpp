// ugv-servo: drives the nodding servo over CAN (CANopen CiA 402, profile position), runs the
// nod profile, publishes SERVO_STATE at the TPDO rate (>= 100 Hz). See docs/servo.md.
#include "servo_config.hpp"
#include "servo_node.hpp"

int main(int argc, char** argv)
{
    ugv::daemon::Daemon d({.name = "ugv-servo", .status_channel = "STATUS_SERVO", .bus_batch_ms = 10}, argc, argv);
    ugv::servo_daemon::ServoConfig config = ugv::servo_daemon::read_config(d.config());
    d.start();
    return ugv::servo_daemon::run(d, std::move(config));
}
