#include "ugv/traverse/odometer.hpp"

#include <algorithm>
#include <cmath>

namespace ugv::traverse {

void Odometer::add(int64_t utime_us, const Eigen::Vector3d& position_m)
{
    if (!position_m.allFinite()) return;
    if (!samples_.empty() && utime_us <= samples_.back().utime_us) samples_.clear();
    const Eigen::Vector2d xy = position_m.head<2>();
    const double odo = samples_.empty() ? 0.0 : samples_.back().odometer_m + (xy - samples_.back().xy_m).norm();
    samples_.push_back({utime_us, xy, odo});
    if (samples_.size() > max_samples_) samples_.pop_front();
}

double Odometer::driven_since(double age_s) const
{
    if (samples_.size() < 2 || !(age_s > 0)) return 0.0;
    const Sample& last = samples_.back();
    const double t = static_cast<double>(last.utime_us) - age_s * 1e6;
    if (t <= static_cast<double>(samples_.front().utime_us)) return last.odometer_m - samples_.front().odometer_m;
    // The first sample at or after t; interpolate with the one before.
    const auto it = std::lower_bound(samples_.begin(), samples_.end(), t,
                                     [](const Sample& s, double v) { return static_cast<double>(s.utime_us) < v; });
    const Sample& b = *it;
    const Sample& a = *(it - 1);
    const double span = static_cast<double>(b.utime_us - a.utime_us);
    const double f = span > 0 ? (t - static_cast<double>(a.utime_us)) / span : 1.0;
    return last.odometer_m - (a.odometer_m + f * (b.odometer_m - a.odometer_m));
}

}  // namespace ugv::traverse
