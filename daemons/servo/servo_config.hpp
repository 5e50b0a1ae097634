// ugv-servo configuration keys (docs/servo.md lists them all).
#pragma once

#include <string>

#include "nod_controller.hpp"
#include "ugv/canopen/drive.hpp"
#include "ugv/nodscan/nod_profile.hpp"
#include "ugv/runtime/config.hpp"

namespace ugv::servo_daemon {

struct ServoConfig
{
    std::string transport = "slcan:/dev/ttyACM0@115200";
    int bitrate = 500000;
    std::string channel = "SERVO_STATE";
    std::string command_channel = "SERVO_COMMAND";
    canopen::DriveConfig drive;
    NodControllerOptions nod;
    nodscan::NodCommand default_profile;
    int64_t control_period_us = 10'000;  // the drive's TPDO period: a set-point per status
    // 0: wake for every frame as it arrives. N: once the drive runs, read the bus on the
    // control tick, and wake for arriving frames only during a window of 5 TPDO periods
    // every N ms, to time the TPDO clock (ServoNode::want_frame_wakeups).
    int64_t frame_wakeup_period_us = 500'000;
    double shutdown_timeout_s = 0.8;
};

ServoConfig read_config(runtime::Config& cfg);

}  // namespace ugv::servo_daemon
