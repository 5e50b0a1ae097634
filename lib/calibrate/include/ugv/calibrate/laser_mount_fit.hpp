// The nodding laser's mount from a recording of flat ground (docs/calibration.md).
//
// The vehicle stands (or drives) on the ground it looks at, so in the body frame that ground
// is the plane z = 0 at every tilt and in every direction. Each beam's body-frame height is
// a function of the tilt axis's roll, pitch, yaw and height (nodscan::beam_point_body); the
// fit finds the ones that put the ground beams at z = 0, by Gauss-Newton on the beams within
// a gate that shrinks to a few robust sigmas, so obstacles and ditches in view are left out.
// A parameter the data cannot pin down (yaw never moves a flat ground's heights) is reported
// as not determined and kept at its initial value.
//
// The servo's tilt zero and the axis's pitch are one angle for this model (R_axis Ry(tilt):
// a zero error is a pitch of the axis), so the fit reports the pitch; the same angle can be
// set as the servo's zero instead.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "ugv/calibrate/param_estimate.hpp"
#include "ugv/nodscan/mount.hpp"

namespace ugv::calibrate {

// One beam: its range, its angle in the scan plane and the tilt the servo reported at its time.
// `block` numbers consecutive stretches of the recording, for the spread of the estimate.
struct LaserBeam
{
    float range_m = 0;
    float beam_angle_rad = 0;
    float tilt_rad = 0;
    int32_t block = 0;
};

struct LaserFitConfig
{
    double min_range_m = 2.0;          // beams nearer than this are left out (the vehicle itself)
    double max_range_m = 12.0;         // and further (a flat lot rarely stays flat further)
    std::size_t min_beams = 5000;      // fewer usable beams: the recording is too short
    double min_tilt_span_deg = 5.0;    // the laser must have nodded at least this much
    double first_gate_m = 1.0;         // ground beams are within this of z = 0 at the start
    double min_gate_m = 0.03;          // the gate never shrinks below this
    double gate_sigmas = 4.0;          // the gate: this many robust sigmas of the residuals
    double min_ground_fraction = 0.3;  // of the usable beams on the ground, or no ground in view
    double max_ground_rms_m = 0.05;    // residual RMS of the ground beams, or the ground is not flat
    double max_sigma_angle_deg = 0.2;  // an angle less certain than this is not determined
    double max_sigma_height_m = 0.02;  // and a height
    int max_iterations = 40;
};

enum LaserParam { kRoll, kPitch, kYaw, kHeight, kLaserParams };

struct LaserFitResult
{
    std::string failure;  // why there is no estimate (empty: there is one)
    std::array<ParamEstimate, kLaserParams> params{};
    nodscan::MountGeometry mount;  // the initial mount with the determined parameters replaced
    std::size_t beams = 0;          // usable beams (within the ranges)
    std::size_t ground_beams = 0;   // of them within the final gate
    double gate_m = 0;
    double rms_before_m = 0;        // the ground beams' height RMS with the initial mount
    double rms_after_m = 0;         // and with the estimate
    double tilt_span_deg = 0;
    int iterations = 0;
    int blocks = 0;                 // blocks with enough ground beams for the spread
};

const char* laser_param_name(LaserParam p);

// Fits the mount to beams of flat ground, starting from `initial` (the configured mount).
// The parameters are the tilt axis's roll, pitch, yaw and height (axis_rpy_rad, axis_xyz_m.z);
// the laser's own placement on the axis is taken as configured.
LaserFitResult fit_laser_mount(const std::vector<LaserBeam>& beams, const nodscan::MountGeometry& initial,
                               const LaserFitConfig& config = {});

}  // namespace ugv::calibrate
