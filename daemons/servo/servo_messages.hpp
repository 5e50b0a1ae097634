// servo_command_t / servo_state_t <-> the drive's and the nod profile's types.
#pragma once

#include <cstdint>

#include "ugv/canopen/drive.hpp"
#include "ugv/nodscan/nod_profile.hpp"
#include "ugv/servo_command_t.hpp"
#include "ugv/servo_state_t.hpp"

namespace ugv::servo_daemon {

// A command's profile (an unknown profile number becomes an invalid kind, which the nod
// controller refuses).
nodscan::NodCommand from_message(const servo_command_t& m, double scan_period_s);
servo_state_t to_message(const canopen::DriveSample& s, nodscan::NodKind profile, uint16_t fault_code, int64_t seq);

}  // namespace ugv::servo_daemon
