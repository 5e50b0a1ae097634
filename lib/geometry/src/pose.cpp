#include "ugv/geometry/pose.hpp"

#include <algorithm>
#include <cmath>

#include "ugv/geometry/rotation.hpp"

namespace ugv::geometry {

RigidTransform RigidTransform::inverse() const
{
    RigidTransform inv;
    inv.rotation = rotation.conjugate();
    inv.translation = -(inv.rotation * translation);
    return inv;
}

RigidTransform RigidTransform::operator*(const RigidTransform& other) const
{
    RigidTransform out;
    out.rotation = (rotation * other.rotation).normalized();
    out.translation = rotation * other.translation + translation;
    return out;
}

bool StampedPose::finite() const
{
    return position_m.allFinite() && orientation.coeffs().allFinite() && orientation.norm() > 0.5 &&
           orientation_covariance_rad2.allFinite();
}

double StampedPose::yaw_rad() const
{
    return yaw_from_quaternion(orientation);
}

double StampedPose::orientation_error_rad2() const
{
    return std::max(0.0, orientation_covariance_rad2.diagonal().maxCoeff());
}

StampedPose interpolate(const StampedPose& a, const StampedPose& b, double fraction)
{
    StampedPose p;
    p.utime_us = a.utime_us + static_cast<int64_t>(std::llround(fraction * static_cast<double>(b.utime_us - a.utime_us)));
    p.position_m = a.position_m + fraction * (b.position_m - a.position_m);
    p.orientation = a.orientation.slerp(fraction, b.orientation);
    p.orientation_covariance_rad2 =
        a.orientation_covariance_rad2 + fraction * (b.orientation_covariance_rad2 - a.orientation_covariance_rad2);
    return p;
}

}  // namespace ugv::geometry
