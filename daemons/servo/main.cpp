// ugv-servo: drives the nodding servo over CAN (CANopen CiA 402, profile position), runs the
// nod profile, publishes SERVO_STATE at the TPDO rate (>= 100 Hz). See docs/servo.md.
#include "servo_app.hpp"
#include "servo_config.hpp"
#include "ugv/daemon/daemon.hpp"

int main(int argc, char** argv)
{
    ugv::daemon::Daemon d({.name = "ugv-servo", .status_channel = "STATUS_SERVO", .bus_batch_ms = 10}, argc, argv);
    ugv::servo::ServoConfig config = ugv::servo::read_config(d.config());
    d.start();
    ugv::servo::ServoApp app(d, std::move(config));
    app.start();
    const int rc = d.run();
    app.shutdown();  // halt, then disable
    return rc;
}
