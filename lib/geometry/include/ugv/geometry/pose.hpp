// Rigid transforms, and the time-stamped vehicle pose with its orientation covariance and
// its interpolation between two poses.
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

// The body pose in the local ENU frame at one time, with the roll/pitch/yaw covariance.
struct StampedPose
{
    int64_t utime_us = 0;                        // time the pose is valid at, us since the epoch
    Eigen::Vector3d position_m{0, 0, 0};         // body origin (the pose's reference point) in ENU
    Eigen::Quaterniond orientation{1, 0, 0, 0};  // body -> ENU
    Eigen::Matrix3d orientation_covariance_rad2 = Eigen::Matrix3d::Zero();  // roll, pitch, yaw

    // Every number finite and the orientation not degenerate (norm > 0.5).
    bool finite() const;
    // Heading of the body X axis projected on the ground (rad, 0 = east, CCW positive).
    double yaw_rad() const;
    // The largest of the roll, pitch and yaw variances (rad^2, >= 0): a bound on the
    // orientation error about any axis (the terrain map's de^2 of eq. 19).
    double orientation_error_rad2() const;
};

// The pose a fraction of the way from a (0) to b (1): position and covariance linear,
// orientation slerp (the shorter way round, so yaw crosses +-pi without a full turn). The
// time is rounded to the microsecond. Fractions outside [0, 1] extrapolate.
StampedPose interpolate(const StampedPose& a, const StampedPose& b, double fraction);

}  // namespace ugv::geometry
