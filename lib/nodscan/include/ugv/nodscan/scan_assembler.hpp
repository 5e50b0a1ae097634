// Turns one 2-D laser scan plus the servo's tilt at each beam's own time into 3-D points in
// the body frame, each with its sensor variance:
//   variance = range_sigma^2 + (range * angle_sigma)^2
// (range noise, plus the encoder angle noise swept out at that range). Beams without a valid
// range (NaN, <= 0, beyond range_max) and beams without a tilt angle are dropped and counted.
#pragma once

#include <algorithm>
#include <array>
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
// Beam i was measured at utime + beam_offset_s(i): an interlaced scan is measured in
// `sweeps` turns of the mirror, sweep_of_phase[i mod sweeps] being the one that took beam i
// (laser_scan_t's sweep layout).
struct ScanView
{
    static constexpr int kMaxSweeps = 8;
    int64_t utime = 0;            // start of the first sweep, us
    double angle_min = 0.0;       // rad, beam 0
    double angle_increment = 0.0; // rad
    double time_increment = 0.0;  // s per beam index
    double range_max = 0.0;       // m; <= 0 means no limit
    int sweeps = 1;
    double sweep_period = 0.0;    // s between sweep starts
    std::array<int8_t, kMaxSweeps> sweep_of_phase{};
    const float* ranges = nullptr;
    std::size_t n = 0;

    // order[k] = the beam phase sweep k measured (laser_scan_t.sweep_order). False, leaving
    // the view as it was, unless order is a permutation of 0..count-1 (count 1..kMaxSweeps)
    // and period is finite and >= 0.
    bool set_sweeps(const int8_t* order, int count, double period);
    double beam_offset_s(std::size_t i) const
    {
        return sweep_of_phase[i % static_cast<std::size_t>(sweeps)] * sweep_period +
               time_increment * static_cast<double>(i);
    }
    // Seconds from utime to the last measured beam (0 without beams).
    double span_s() const;
};

// A view of a laser_scan_t-like message's ranges (valid while the message lives; n bounded
// by the array). A template, so this library never sees LCM. A sweep layout that is not one
// (ScanView::set_sweeps) gives sweeps = 0; nsweeps 0 or 1 is no interlacing.
template <class LaserScan>
ScanView scan_view_of(const LaserScan& s)
{
    ScanView v;
    v.utime = s.utime;
    v.angle_min = s.angle_min;
    v.angle_increment = s.angle_increment;
    v.time_increment = s.time_increment;
    v.range_max = s.range_max;
    const int sweeps = std::min<int>(s.nsweeps, static_cast<int>(s.sweep_order.size()));
    if (s.nsweeps > 1 && !v.set_sweeps(s.sweep_order.data(), sweeps, s.sweep_period)) v.sweeps = 0;
    if (s.nsweeps < 0) v.sweeps = 0;
    v.ranges = s.ranges.data();
    v.n = std::min<std::size_t>(s.ranges.size(), static_cast<std::size_t>(std::max(0, s.nranges)));
    return v;
}

struct PointCloud
{
    int64_t utime = 0;
    Eigen::Vector3d sensor_origin{0.0, 0.0, 0.0};  // laser origin in the body frame at utime
    std::vector<float> x, y, z, range, variance, time_offset;
    std::vector<uint32_t> beam;  // the scan's beam index of each point
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
    std::vector<double> tilt_, phase_tilt_;
    std::vector<uint8_t> tilt_ok_, phase_ok_;
};

}  // namespace ugv::nodscan
