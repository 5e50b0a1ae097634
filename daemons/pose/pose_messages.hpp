// Conversions between the LCM messages and the estimator's plain structs.
#pragma once

#include <ugv/gps_fix_t.hpp>
#include <ugv/gps_velocity_t.hpp>
#include <ugv/imu_t.hpp>
#include <ugv/pose_t.hpp>

#include "ugv/estimation/pose_estimator.hpp"

namespace ugv::pose_daemon {

estimation::GpsFix to_fix(const gps_fix_t& m);
estimation::GpsVelocity to_velocity(const gps_velocity_t& m);
estimation::ImuSample to_imu(const imu_t& m);
pose_t to_message(const estimation::PoseEstimate& p, int64_t seq);

}  // namespace ugv::pose_daemon
