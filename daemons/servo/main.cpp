// ugv-servo: drives the nodding servo over CAN (CANopen CiA 402, profile position), runs the
// nod profile, publishes SERVO_STATE at the TPDO rate (>= 100 Hz). See docs/servo.md.
#include "servo_config.hpp"
#include "servo_node.hpp"

#include <cstring>
#include <vector>

int main(int argc, char** argv)
{
    // --probe: print what the drive offers and the bring-up plan, move nothing, exit.
    std::vector<char*> args;
    bool probe = false;
    for (int i = 0; i < argc; ++i) {
        if (i > 0 && std::strcmp(argv[i], "--probe") == 0) probe = true;
        else args.push_back(argv[i]);
    }
    argc = static_cast<int>(args.size());
    argv = args.data();
    ugv::daemon::Daemon d({.name = "ugv-servo", .status_channel = "STATUS_SERVO", .bus_batch_ms = 10}, argc, argv);
    ugv::servo_daemon::ServoConfig config = ugv::servo_daemon::read_config(d.config());
    if (probe) return ugv::servo_daemon::probe(config);
    d.start();
    return ugv::servo_daemon::run(d, std::move(config));
}
