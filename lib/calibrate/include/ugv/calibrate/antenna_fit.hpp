// The GPS antenna's lever arm from a drive with turns (docs/calibration.md, "The GPS antenna").
//
// On level ground, with the body's reference point moving without sideslip (the middle of the
// rear axle of a car-like vehicle, as the simulator's vehicle), the antenna at l = (x, y, z)
// moves in the body frame at
//     (v - w y, w x)
// with v the reference point's speed and w the yaw rate. So:
//  - x: the antenna's sideways velocity in a turn. The heading is the IMU's yaw rate
//    integrated; its offset, scale and drift are fitted with x (they act in straight driving
//    too, x only while turning): v_lat = x w + v_fwd (c + k psi + d t).
//  - y: the forward velocity against the reference point's speed, which comes from the
//    centripetal acceleration a_lat = v w:  f_lat - w v_fwd = y w^2 + b + e f_fwd, with b the
//    accelerometer's tilt (level ground, and the IMU's own roll) and e the IMU's residual yaw.
//    Its signal is w^2 y: a 0.1 deg tilt that changes between the turn and the straights is
//    0.017 m/s^2, 0.4 m of y at 0.2 rad/s. y is relative to the IMU's lateral position.
//  - z is not observable on level ground.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "ugv/calibrate/param_estimate.hpp"

namespace ugv::calibrate {

// One IMU sample in the body frame (as ugv-imu publishes it).
struct ImuRateSample
{
    double t_s = 0;
    double yaw_rate_radps = 0;  // body z rate
    double accel_fwd_mps2 = 0;  // specific force, body x
    double accel_lat_mps2 = 0;  // and body y
};

// One GPS velocity: the antenna's horizontal velocity at its measurement time.
struct GpsVelocitySample
{
    double t_s = 0;
    double speed_mps = 0;
    double track_enu_rad = 0;  // direction of motion, ENU (0 = east, counter-clockwise)
};

// A GPS velocity with the IMU around its time.
struct AntennaSample
{
    double t_s = 0;
    double speed_mps = 0, track_enu_rad = 0;
    double heading_rad = 0;     // the integrated yaw rate (any origin)
    double yaw_rate_radps = 0;  // mean over the window
    double accel_fwd_mps2 = 0, accel_lat_mps2 = 0;
};

// The GPS velocities within the IMU's time span, each with the IMU's mean over +/- window_s
// (the default: every IMU sample of a 4 Hz GPS velocity once)
// and the integrated heading at its time. Both inputs sorted by time.
std::vector<AntennaSample> antenna_samples(const std::vector<ImuRateSample>& imu,
                                           const std::vector<GpsVelocitySample>& gps, double window_s = 0.125);

struct AntennaFitConfig
{
    double min_speed_mps = 0.5;     // slower GPS velocities are left out (their direction is noise)
    std::size_t min_samples = 30;   // moving samples, or the log is too short
    double turn_rate_radps = 0.05;  // a sample turns faster than this
    double min_turn_deg = 45.0;     // heading change while turning, or there are no turns
    double max_sigma_m = 0.05;      // a less certain coordinate is not determined
    double gate_sigmas = 5.0;       // residuals beyond this many RMS are outliers (refit once)
    // How well GPS_VEL's and the IMU's stamps agree: a heading read this late in a turn is
    // x's error times the speed, so x's sigma includes speed x this (its formal one leaves it out).
    double stamp_alignment_s = 0.005;
};

struct AntennaFitResult
{
    std::string failure;  // why there is no estimate (empty: there is one)
    ParamEstimate x, y;   // m, body frame; `initial` as given to fit_antenna
    std::size_t samples = 0;       // moving, used
    std::size_t turning_samples = 0;
    double turn_deg = 0;           // heading change while turning
    double max_yaw_rate_radps = 0;
    double lateral_rms_mps = 0;    // residual of the sideways velocity fit
    double accel_rms_mps2 = 0;     // and of the centripetal one
    double heading_scale = 0;      // k: the integrated heading's scale error
};

// Fits the lever arm's x and y; initial_x, initial_y (the configured arm) are only reported.
AntennaFitResult fit_antenna(const std::vector<AntennaSample>& samples, double initial_x_m, double initial_y_m,
                             const AntennaFitConfig& config = {});

}  // namespace ugv::calibrate
