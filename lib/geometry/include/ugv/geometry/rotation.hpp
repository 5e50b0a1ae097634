// Rotations in the project's frames (docs/ARCHITECTURE.md, "Frames, time and units"): body
// X forward, Y left, Z up; world local ENU; yaw 0 = east, counter-clockwise positive.
//
// Euler angles are the Z-Y-X (yaw, pitch, roll) sequence: R_body->ENU = Rz(yaw) Ry(pitch) Rx(roll).
// A small attitude error is expressed as a rotation vector in the world (ENU) frame:
// R_true = exp([dtheta]x) R_estimate.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ugv::geometry {

struct Euler
{
    double roll = 0.0;   // rad, about body X
    double pitch = 0.0;  // rad, about body Y
    double yaw = 0.0;    // rad, about ENU up, 0 = east, counter-clockwise positive
};

// Wraps an angle into (-pi, pi]: -pi itself becomes +pi.
double wrap_angle(double rad);

// Body -> ENU rotation from Z-Y-X Euler angles.
Eigen::Quaterniond quaternion_from_euler(const Euler& e);
// Z-Y-X Euler angles of a body -> ENU rotation (pitch in [-pi/2, pi/2]).
Euler euler_from_quaternion(const Eigen::Quaterniond& q);
// The same rotation as a matrix, multiplied out from the angles' sines and cosines (no
// quaternion on the way, so a zero angle contributes exact zeros and ones).
Eigen::Matrix3d rotation_from_euler(const Euler& e);

// Heading of the body X axis projected on the ground (rad, 0 = east, counter-clockwise
// positive, in [-pi, pi]): the Z-Y-X yaw. q is taken as a unit quaternion, not normalised.
double yaw_from_quaternion(const Eigen::Quaterniond& q);

// A plane rotation by angle (rad, counter-clockwise): [c -s; s c].
Eigen::Matrix2d rotation_2d(double angle);

// A rotation about +Y by angle (rad): turns +X towards -Z for a positive angle.
Eigen::Matrix3d rotation_y(double angle);
// A rotation about ENU up by yaw (rad).
Eigen::Matrix3d rotation_z(double yaw);

// Track over ground as GPS receivers report it (rad, clockwise from true north) to ENU yaw
// (rad, counter-clockwise from east), and back. Both results are wrapped to (-pi, pi].
double enu_yaw_from_track(double track_rad);
double track_from_enu_yaw(double yaw_rad);

// d(roll, pitch, yaw) / d(dtheta) for a world-frame small rotation dtheta applied to the
// rotation with Euler angles e: the matrix that maps an attitude error covariance in the
// world frame into a roll/pitch/yaw covariance. Singular at pitch = +-pi/2.
Eigen::Matrix3d euler_jacobian_world(const Euler& e);

// exp() of a rotation vector (rad) as a unit quaternion; exact for any angle.
Eigen::Quaterniond quaternion_exp(const Eigen::Vector3d& rotation_vector);
// log() of a unit quaternion as a rotation vector with angle in [0, pi].
Eigen::Vector3d quaternion_log(const Eigen::Quaterniond& q);

// The skew-symmetric (cross product) matrix: skew(a) * b == a.cross(b).
Eigen::Matrix3d skew(const Eigen::Vector3d& a);

}  // namespace ugv::geometry
