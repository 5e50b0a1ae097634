#include "ugv/nodscan/servo_history.hpp"

#include <algorithm>
#include <cmath>

namespace ugv::nodscan {

bool ServoHistory::add(const TiltSample& s)
{
    if (!std::isfinite(s.angle_rad) || !samples_.add(s)) {
        ++rejected_;
        return false;
    }
    return true;
}

std::optional<double> ServoHistory::angle_at(int64_t t, int64_t max_extrapolation_us) const
{
    double a = 0.0;
    uint8_t ok = 0;
    angles_at(t, 0.0, 1, max_extrapolation_us, &a, &ok);
    if (!ok) return std::nullopt;
    return a;
}

std::size_t ServoHistory::angles_at(int64_t t0, double dt, std::size_t n, int64_t max_extra, double* out,
                                    uint8_t* valid) const
{
    if (samples_.empty()) {
        std::fill(valid, valid + n, uint8_t{0});
        return 0;
    }
    const int64_t newest = samples_.newest().utime_us;
    const int64_t oldest = samples_.oldest().utime_us;
    // First sample at or after t0 (the upper bracket of beam 0).
    std::size_t hi = samples_.first_not_before(t0);
    std::size_t count = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const double t = static_cast<double>(t0) + dt * static_cast<double>(i);
        while (hi < samples_.size() && static_cast<double>(samples_[hi].utime_us) < t) ++hi;
        if (t < static_cast<double>(oldest) || t > static_cast<double>(newest + max_extra)) {
            valid[i] = 0;
            continue;
        }
        if (samples_.size() == 1) {
            out[i] = samples_[0].angle_rad;  // only one sample: it can only be held
        } else {
            // Bracket [lo, hi]; beyond the newest, extend the last segment.
            const std::size_t h = std::clamp<std::size_t>(hi, 1, samples_.size() - 1);
            const TiltSample& a = samples_[h - 1];
            const TiltSample& b = samples_[h];
            const double f = (t - static_cast<double>(a.utime_us)) / static_cast<double>(b.utime_us - a.utime_us);
            out[i] = a.angle_rad + f * (b.angle_rad - a.angle_rad);
        }
        valid[i] = 1;
        ++count;
    }
    return count;
}

}  // namespace ugv::nodscan
