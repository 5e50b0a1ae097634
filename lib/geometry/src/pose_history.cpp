#include "ugv/geometry/pose_history.hpp"

namespace ugv::geometry {

PoseHistory::AddResult PoseHistory::add(const StampedPose& pose)
{
    if (!pose.finite()) return AddResult::non_finite;
    // Normalised only after the check: finite() refuses a near-zero quaternion that
    // normalising would have turned into a valid-looking one.
    StampedPose p = pose;
    p.orientation.normalize();
    return poses_.add(p) ? AddResult::added : AddResult::out_of_order;
}

PoseHistory::Lookup PoseHistory::at(int64_t utime_us, StampedPose& out) const
{
    if (poses_.empty()) return Lookup::empty;
    if (utime_us < poses_.oldest().utime_us) return Lookup::before_history;
    if (utime_us > poses_.newest().utime_us) return Lookup::after_history;
    const std::size_t i = poses_.first_not_before(utime_us);
    if (poses_[i].utime_us == utime_us) {
        out = poses_[i];
        return Lookup::ok;
    }
    const StampedPose& a = poses_[i - 1];
    const StampedPose& b = poses_[i];
    const double fraction =
        static_cast<double>(utime_us - a.utime_us) / static_cast<double>(b.utime_us - a.utime_us);
    out = interpolate(a, b, fraction);
    out.utime_us = utime_us;
    return Lookup::ok;
}

}  // namespace ugv::geometry
