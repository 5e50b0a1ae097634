// The driver's plain structs -> the ugv LCM types (the only place that knows both).
#pragma once

#include <ugv/gps_fix_t.hpp>
#include <ugv/gps_velocity_t.hpp>

#include "ugv/novatel/interpreter.hpp"

namespace ugv::gps_daemon {

ugv::gps_fix_t to_message(const novatel::Fix& fix, int64_t seq);
ugv::gps_velocity_t to_message(const novatel::VelocityFix& velocity, int64_t seq);

}  // namespace ugv::gps_daemon
