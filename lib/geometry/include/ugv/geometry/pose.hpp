// Rigid transforms and time-stamped poses (body -> world), with interpolation between two
// poses at an intermediate time: linear in position, spherical-linear in orientation.
#pragma once

#include <cstdint>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ugv::geometry {

// A rigid transform: x_parent = rotation * x_child + translation.
struct RigidTransform
{
    Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
    Eigen::Vector3d translation = Eigen::Vector3d::Zero();

    Eigen::Vector3d apply(const Eigen::Vector3d& x) const { return rotation * x + translation; }
    RigidTransform inverse() const;
    // (*this) * other: first other, then this.
    RigidTransform operator*(const RigidTransform& other) const;
};

// The body -> world transform at utime (us since the epoch).
struct StampedPose
{
    int64_t utime = 0;
    RigidTransform body_to_world;
};

// The pose at utime between a and b (a.utime <= utime <= b.utime; outside that range it
// extrapolates linearly in position and clamps the orientation). a.utime == b.utime gives a.
StampedPose interpolate(const StampedPose& a, const StampedPose& b, int64_t utime);

}  // namespace ugv::geometry
