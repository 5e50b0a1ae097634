// Where the nodding laser sits: the laser on the tilt axis, the tilt axis on the vehicle.
//
//   p_body = R_axis * Ry(tilt) * (R_laser * p_laser + t_laser) + t_axis
//
// Frames: body X forward, Y left, Z up. The tilt frame has its origin on the tilt axis and
// its Y axis along it; at tilt 0 it is oriented by rpy_axis in the body frame. A positive
// tilt turns +X towards -Z (nose down), i.e. a rotation by +tilt about +Y. The laser frame is
// the scanner's own: beam angle 0 along +X, counter-clockwise (towards +Y) positive, scan
// plane z = 0; it is placed in the tilt frame by t_laser and rpy_laser.
#pragma once

#include <Eigen/Core>

namespace ugv::nodscan {

struct MountGeometry
{
    Eigen::Vector3d axis_xyz_m{0.0, 0.0, 0.0};  // tilt axis origin in the body frame
    Eigen::Vector3d axis_rpy_rad{0.0, 0.0, 0.0};
    Eigen::Vector3d laser_xyz_m{0.0, 0.0, 0.0};  // laser origin in the tilt frame (offset from the axis)
    Eigen::Vector3d laser_rpy_rad{0.0, 0.0, 0.0};
};

// R_axis and R_laser: roll, pitch, yaw (rad) applied as Rz(yaw) * Ry(pitch) * Rx(roll).
Eigen::Matrix3d rotation_rpy(const Eigen::Vector3d& rpy_rad);

// Rotation about +Y by tilt (positive = nose down).
Eigen::Matrix3d tilt_rotation(double tilt_rad);

// The body-frame position of a point at range r along a beam at beam_angle_rad, with the
// laser tilted by tilt_rad (reference implementation; the assembler computes the same faster).
Eigen::Vector3d beam_point_body(const MountGeometry& mount, double tilt_rad, double beam_angle_rad, double range_m);
// The laser origin in the body frame at this tilt.
Eigen::Vector3d laser_origin_body(const MountGeometry& mount, double tilt_rad);
// The unit direction of a beam in the tilt frame (R_laser times the beam in the scan plane).
Eigen::Vector3d beam_direction_tilt_frame(const Eigen::Matrix3d& r_laser, double beam_angle_rad);

}  // namespace ugv::nodscan
