#include "ugv/terrain/pose_history.hpp"

#include <algorithm>
#include <cmath>

namespace ugv::terrain {

bool Pose::finite() const
{
    return position_m.allFinite() && orientation.coeffs().allFinite() && orientation.norm() > 0.5 &&
           orientation_covariance_rad2.allFinite();
}

double Pose::yaw_rad() const
{
    const Eigen::Vector3d forward = orientation * Eigen::Vector3d::UnitX();
    return std::atan2(forward.y(), forward.x());
}

double Pose::orientation_error_rad2() const
{
    return std::max(0.0, orientation_covariance_rad2.diagonal().maxCoeff());
}

double wrap_angle_rad(double a)
{
    a = std::remainder(a, 2.0 * M_PI);
    return a <= -M_PI ? a + 2.0 * M_PI : a;
}

PoseHistory::AddResult PoseHistory::add(const Pose& pose)
{
    if (!pose.finite()) return AddResult::non_finite;
    if (!poses_.empty() && pose.utime_us <= poses_.back().utime_us) return AddResult::out_of_order;
    Pose p = pose;
    p.orientation.normalize();
    poses_.push_back(p);
    while (poses_.size() > 2 && poses_.front().utime_us < p.utime_us - span_us_) poses_.pop_front();
    return AddResult::added;
}

Pose interpolate(const Pose& a, const Pose& b, double fraction)
{
    Pose p;
    p.utime_us = a.utime_us + static_cast<int64_t>(std::llround(fraction * static_cast<double>(b.utime_us - a.utime_us)));
    p.position_m = a.position_m + fraction * (b.position_m - a.position_m);
    p.orientation = a.orientation.slerp(fraction, b.orientation);
    p.orientation_covariance_rad2 =
        a.orientation_covariance_rad2 + fraction * (b.orientation_covariance_rad2 - a.orientation_covariance_rad2);
    return p;
}

PoseHistory::Lookup PoseHistory::at(int64_t utime_us, Pose& out) const
{
    if (poses_.empty()) return Lookup::empty;
    if (utime_us < poses_.front().utime_us) return Lookup::before_history;
    if (utime_us > poses_.back().utime_us) return Lookup::after_history;
    // First pose not older than utime_us.
    auto it = std::lower_bound(poses_.begin(), poses_.end(), utime_us,
                               [](const Pose& p, int64_t t) { return p.utime_us < t; });
    if (it->utime_us == utime_us) {
        out = *it;
        return Lookup::ok;
    }
    const Pose& b = *it;
    const Pose& a = *(it - 1);
    const double fraction =
        static_cast<double>(utime_us - a.utime_us) / static_cast<double>(b.utime_us - a.utime_us);
    out = interpolate(a, b, fraction);
    out.utime_us = utime_us;
    return Lookup::ok;
}

}  // namespace ugv::terrain
