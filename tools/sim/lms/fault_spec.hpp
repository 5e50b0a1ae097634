// `--fault` flags of ugv-sim lms:
//   garbage[:P]           1-40 random bytes before a telegram, with probability P (0.1)
//   bitflip[:P]           one bit flipped in a scan, with probability P (0.05)
//   ber[:P]               bit error rate per byte: each byte sent has one bit flipped with
//                         probability P (0.001)
//   truncate[:P]          a scan cut short (its first 1..size-1 bytes only) with probability
//                         P (0.1); the next scan follows as usual
//   silence[:EVERY[:FOR]] every EVERY s (5) the device sends nothing for FOR s (1)
//   disappear[:AFTER[:GONE]] after AFTER s (5) the port vanishes for GONE s (1), then a freshly
//                         powered device (9600 baud, not streaming) appears at the same path;
//                         repeats
#pragma once

#include <string>

#include "lms_emulator.hpp"

namespace ugv::sim::lms {

struct FaultPlan
{
    Faults device;
    double disappear_after_s = 0.0;  // 0 = never
    double disappear_for_s = 1.0;
};

// Adds one --fault flag to plan. Throws std::invalid_argument with a one-line reason.
void add_fault(const std::string& spec, FaultPlan& plan);

}  // namespace ugv::sim::lms
