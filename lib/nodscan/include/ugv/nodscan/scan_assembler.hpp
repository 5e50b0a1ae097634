// Turns one 2-D laser scan plus the servo's tilt at each beam's own time into 3-D points in
// the body frame, each with its sensor variance:
//   variance = range_sigma^2 + (range * angle_sigma)^2
// (range noise, plus the encoder angle noise swept out at that range). Beams without a valid
// range (NaN, <= 0, beyond range_max) and beams without a tilt angle are dropped and counted.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "ugv/nodscan/mount.hpp"
#include "ugv/nodscan/servo_history.hpp"

namespace ugv::nodscan {

struct AssemblerConfig
{
    MountGeometry mount;
    double range_sigma_m = 0.01;       // 1-sigma range noise of the laser
    double angle_sigma_rad = 0.001;    // 1-sigma tilt angle noise (encoder and interpolation)
    int64_t max_extrapolation_us = 20'000;  // how far past the newest servo sample a beam may be
};

// A scan as the assembler needs it (the daemon points it at a laser_scan_t's arrays).
struct ScanView
{
    int64_t utime = 0;            // time of beam 0, us
    double angle_min = 0.0;       // rad, beam 0
    double angle_increment = 0.0; // rad
    double time_increment = 0.0;  // s between beams
    double range_max = 0.0;       // m; <= 0 means no limit
    const float* ranges = nullptr;
    std::size_t n = 0;
};

struct PointCloud
{
    int64_t utime = 0;
    Eigen::Vector3d sensor_origin{0.0, 0.0, 0.0};  // laser origin in the body frame at utime
    std::vector<float> x, y, z, range, variance, time_offset;
    void clear();
    std::size_t size() const { return x.size(); }
};

struct AssembleStats
{
    std::size_t points = 0;
    std::size_t dropped_invalid = 0;   // no valid range
    std::size_t dropped_no_angle = 0;  // no servo angle at the beam's time
};

class ScanAssembler
{
public:
    explicit ScanAssembler(AssemblerConfig config);

    // Fills out (cleared first) from scan, using the tilt history. Never allocates once the
    // buffers have grown to the scan size.
    AssembleStats assemble(const ScanView& scan, const ServoHistory& servo, PointCloud& out);

    // The time of the scan's last beam, us: the servo must reach it for a full bracket.
    static int64_t last_beam_utime(const ScanView& scan);

    const AssemblerConfig& config() const { return config_; }

private:
    void prepare_directions(const ScanView& scan);

    AssemblerConfig config_;
    Eigen::Matrix3d r_axis_;
    // Cached per scan layout: unit beam directions in the tilt frame.
    double cached_min_ = 0.0, cached_inc_ = 0.0;
    std::size_t cached_n_ = 0;
    std::vector<double> ux_, uy_, uz_;
    std::vector<double> tilt_;
    std::vector<uint8_t> tilt_ok_;
};

}  // namespace ugv::nodscan
