// The vehicle pose the map needs: position and orientation in the local ENU frame, and the
// roll/pitch/yaw covariance that gives the orientation error of eq. 19.
#pragma once

#include <cstdint>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ugv::terrain {

struct Pose
{
    int64_t utime_us = 0;                 // time the pose is valid at
    Eigen::Vector3d position_m{0, 0, 0};  // body origin (the reference point of the pose) in ENU
    Eigen::Quaterniond orientation{1, 0, 0, 0};  // body -> ENU
    Eigen::Matrix3d orientation_covariance_rad2 = Eigen::Matrix3d::Zero();  // roll, pitch, yaw

    bool finite() const;
    // Heading of the body X axis projected on the ground (rad, 0 = east, CCW positive).
    double yaw_rad() const;
    // The squared orientation error (de^2 of eq. 19, rad^2): the largest of the roll, pitch
    // and yaw variances, so the error sphere bounds every axis.
    double orientation_error_rad2() const;
};

// Wraps an angle to (-pi, pi].
double wrap_angle_rad(double a);

}  // namespace ugv::terrain
