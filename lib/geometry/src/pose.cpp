#include "ugv/geometry/pose.hpp"

#include <algorithm>

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

StampedPose interpolate(const StampedPose& a, const StampedPose& b, int64_t utime)
{
    if (b.utime == a.utime) {
        return a;
    }
    const double s = static_cast<double>(utime - a.utime) / static_cast<double>(b.utime - a.utime);
    StampedPose out;
    out.utime = utime;
    out.body_to_world.translation =
        a.body_to_world.translation + s * (b.body_to_world.translation - a.body_to_world.translation);
    out.body_to_world.rotation =
        a.body_to_world.rotation.slerp(std::clamp(s, 0.0, 1.0), b.body_to_world.rotation).normalized();
    return out;
}

}  // namespace ugv::geometry
