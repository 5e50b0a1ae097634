// The IMU's mounting from a recording (docs/calibration.md, "The IMU's mounting").
//
// The samples are what ugv-imu publishes: already turned into the body frame by the
// configured mounting M_c, so a wrong mounting leaves a residual rotation D (true body ->
// reported body) in them: f_reported = D f_body, and the true mounting is D^T M_c.
//  - Standing still (or driving straight at a constant speed: the IMU cannot tell them
//    apart) the specific force is gravity alone: its direction in the reported frame is D's
//    "up", so roll and pitch -- if the body stood level. A ground slope of s deg is an error
//    of up to s deg; standing in two opposite directions on the same spot averages it out.
//  - Driving straight and speeding up or braking, the acceleration is along the body's X:
//    its direction in the reported frame, around "up", is D's yaw. Gravity is taken out with
//    the IMU's own attitude (orientation), which follows the terrain's tilt.
// Turning samples are left out (their acceleration is sideways and depends on the IMU's place).
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ugv/calibrate/param_estimate.hpp"

namespace ugv::calibrate {

struct ImuMountSample
{
    double t_s = 0;
    Eigen::Vector3d accel_mps2 = Eigen::Vector3d::Zero();  // specific force, reported body frame
    Eigen::Vector3d rate_radps = Eigen::Vector3d::Zero();
    // The unit's own "up" in the reported body frame (its orientation's inverse applied to
    // ENU up); a sample without one serves only gravity.
    Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
    bool has_up = false;
};

struct ImuMountFitConfig
{
    double still_window_s = 1.0;            // still: over this window around a sample ...
    double still_rate_radps = 0.02;         // ... every rate below this
    double still_accel_spread_mps2 = 0.15;  // ... the specific force within this of its mean
    double still_kinematic_mps2 = 0.05;     // ... and its mean less the unit's gravity below this
    double min_still_s = 3.0;               // still time needed, or there is no static period
    double straight_rate_radps = 0.02;      // an acceleration sample turns slower than this
    double min_accel_mps2 = 0.3;            // and accelerates at least this much
    std::size_t min_accel_samples = 25;     // fewer: yaw is not determined
    double max_sigma_deg = 0.2;             // a less certain angle is not determined
};

enum ImuAngle { kImuRoll, kImuPitch, kImuYaw, kImuAngles };

struct ImuMountFitResult
{
    std::string failure;  // why there is no estimate (empty: there is one)
    // The mounting's roll, pitch, yaw (rad, as ugv-imu's mount_rpy_deg); `initial` the configured.
    std::array<ParamEstimate, kImuAngles> params{};
    Eigen::Vector3d residual_rpy_rad = Eigen::Vector3d::Zero();  // D's angles: the configured mounting's error
    double span_s = 0;
    double still_s = 0;
    int still_periods = 0;
    double gravity_mps2 = 0;       // the mean specific force's magnitude while still
    std::size_t accel_samples = 0;
    int accel_events = 0;
    double max_accel_mps2 = 0;
};

// Samples sorted by time; configured_rpy_rad is ugv-imu's mount_rpy_deg in radians.
ImuMountFitResult fit_imu_mount(const std::vector<ImuMountSample>& samples, const Eigen::Vector3d& configured_rpy_rad,
                                const ImuMountFitConfig& config = {});

}  // namespace ugv::calibrate
