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

#include <array>

namespace ugv::nodscan {

using Vec3 = std::array<double, 3>;
using Mat3 = std::array<std::array<double, 3>, 3>;  // row-major

// Rotation from roll, pitch, yaw (rad) applied as Rz(yaw) * Ry(pitch) * Rx(roll).
Mat3 rotation_rpy(double roll, double pitch, double yaw);
Vec3 multiply(const Mat3& m, const Vec3& v);
Mat3 multiply(const Mat3& a, const Mat3& b);

struct MountGeometry
{
    Vec3 axis_xyz_m{0.0, 0.0, 0.0};  // tilt axis origin in the body frame
    Vec3 axis_rpy_rad{0.0, 0.0, 0.0};
    Vec3 laser_xyz_m{0.0, 0.0, 0.0};  // laser origin in the tilt frame (offset from the axis)
    Vec3 laser_rpy_rad{0.0, 0.0, 0.0};
};

// Rotation about +Y by tilt (positive = nose down).
Mat3 tilt_rotation(double tilt_rad);

// The body-frame position of a point at range r along a beam at beam_angle_rad, with the
// laser tilted by tilt_rad (reference implementation; the assembler computes the same faster).
Vec3 beam_point_body(const MountGeometry& mount, double tilt_rad, double beam_angle_rad, double range_m);
// The laser origin in the body frame at this tilt.
Vec3 laser_origin_body(const MountGeometry& mount, double tilt_rad);

}  // namespace ugv::nodscan
