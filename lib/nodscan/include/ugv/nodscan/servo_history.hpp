// The recent tilt angles of the servo, in time order, with linear interpolation at any time
// inside (and a short extrapolation beyond) the samples. The storage is lib/geometry's
// TimeHistory, as for the poses; the lookup is the servo's own: fractional times, a batch of
// equally spaced beams in one pass, and the bounded extrapolation a pose never gets.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>

#include "ugv/geometry/history.hpp"

namespace ugv::nodscan {

struct TiltSample
{
    int64_t utime_us = 0;  // us since the epoch
    double angle_rad = 0.0;
};

class ServoHistory
{
public:
    // keep_us: samples older than the newest minus keep_us are forgotten (2 s default).
    explicit ServoHistory(int64_t keep_us = 2'000'000) : samples_(keep_us) {}

    // False (and counted) when the sample is not newer than the last one or not finite.
    bool add(const TiltSample& sample);

    // The angle at t: interpolated between the bracketing samples, or extrapolated from the
    // last two when t is at most max_extrapolation_us beyond the newest (the bounded wait ran
    // out), nullopt otherwise (too old, or too far ahead).
    std::optional<double> angle_at(int64_t t_us, int64_t max_extrapolation_us = 0) const;

    // Evaluates n equally spaced times t0 + i * dt_us in one pass (times must increase):
    // out[i] = angle, valid[i] = 1 when there was one. Returns the number of valid ones.
    std::size_t angles_at(int64_t t0_us, double dt_us, std::size_t n, int64_t max_extrapolation_us, double* out,
                          uint8_t* valid) const;

    bool empty() const { return samples_.empty(); }
    int64_t newest_utime() const { return samples_.empty() ? INT64_MIN : samples_.newest().utime_us; }
    int64_t oldest_utime() const { return samples_.empty() ? INT64_MIN : samples_.oldest().utime_us; }
    std::size_t size() const { return samples_.size(); }
    uint64_t rejected() const { return rejected_; }

private:
    geometry::TimeHistory<TiltSample> samples_;
    uint64_t rejected_ = 0;
};

}  // namespace ugv::nodscan
