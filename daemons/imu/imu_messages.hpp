// A session sample -> ugv::imu_t (the only place the daemon touches the message layout).
#pragma once

#include <cstdint>

#include <ugv/imu_t.hpp>

#include "ugv/microstrain_gx1/session.hpp"

namespace ugv::imu_daemon {

ugv::imu_t to_message(const microstrain_gx1::Sample& s, int64_t seq, float orientation_sigma_rad);

}  // namespace ugv::imu_daemon
