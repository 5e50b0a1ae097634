// THE one place where the 3DM-GX1's NED-style attitude becomes the project's convention
// (docs/ARCHITECTURE.md, "Frames, time and units"): body frame X forward, Y left, Z up
// (FLU); world frame ENU; the quaternion rotates body vectors into ENU; yaw 0 = east,
// counter-clockwise positive.
//
// The device: sensor axes X forward, Y right, Z down (FRD); Euler angles roll, pitch, yaw
// (ZYX) of FRD relative to NED, yaw from magnetic north clockwise. Then
//   R_enu_flu = N * Rz(declination) * R_ned_frd * F
// with F = diag(1, -1, -1) (FLU -> FRD, a half turn about X) and N the NED -> ENU swap
// (a half turn about (1, 1, 0)/sqrt 2). In Euler terms: roll stays, pitch changes sign,
// yaw_enu = pi/2 - (yaw_ned + declination).
//
// Assumptions (the fact sheet does not say; UNVERIFIED on hardware): the device quaternion
// is sensor -> NED (Hamilton, w first) like the Euler angles; the orientation matrix M maps
// NED vectors into sensor axes (M = R_ned_frd transposed); vectors are specific force etc.
// in the FRD sensor axes. A mounting rotation turns the sensor's FLU axes into body axes.
#pragma once

#include <Eigen/Geometry>

#include "ugv/microstrain_gx1/scaling.hpp"

namespace ugv::microstrain_gx1 {

// An attitude in the project convention.
struct EnuAttitude
{
    Eigen::Quaterniond q_enu_body{1, 0, 0, 0};  // body FLU -> ENU, unit, w >= 0
    double roll_rad = 0;   // about body X, right side down positive
    double pitch_rad = 0;  // about body Y (left), nose DOWN positive (right-handed FLU)
    double yaw_rad = 0;    // heading from east, counter-clockwise positive, (-pi, pi]
};

// A sample in body FLU / world ENU, SI units.
struct Measurement
{
    bool has_orientation = false;
    bool has_rate = false, has_accel = false, has_mag = false;
    EnuAttitude attitude;
    Eigen::Vector3d rate_radps = Eigen::Vector3d::Zero();
    Eigen::Vector3d accel_mps2 = Eigen::Vector3d::Zero();
    Eigen::Vector3d mag_gauss = Eigen::Vector3d::Zero();
};

// ZYX Euler angles -> rotation matrix R = Rz(yaw) Ry(pitch) Rx(roll) (any right-handed pair).
Eigen::Matrix3d rotation_from_euler(double roll, double pitch, double yaw);
// The ZYX Euler angles of R (pitch in [-pi/2, pi/2]).
Eigen::Vector3d euler_from_rotation(const Eigen::Matrix3d& r);  // (roll, pitch, yaw)

// R_enu_flu from R_ned_frd (the device's sensor -> NED rotation), with magnetic declination
// (east positive) turning magnetic into true north.
Eigen::Matrix3d enu_flu_from_ned_frd(const Eigen::Matrix3d& r_ned_frd, double declination_rad = 0);
EnuAttitude attitude_from_rotation(const Eigen::Matrix3d& r_enu_body);
// Device NED Euler angles -> project attitude (of the sensor's FLU axes).
EnuAttitude enu_from_ned_euler(double roll, double pitch, double yaw, double declination_rad = 0);
// Device quaternion (w, x, y, z; sensor FRD -> NED) -> project attitude.
EnuAttitude enu_from_ned_quaternion(const Eigen::Quaterniond& q_ned_frd, double declination_rad = 0);
// Sensor FRD vector -> sensor FLU vector.
inline Eigen::Vector3d flu_from_frd(const Eigen::Vector3d& v) { return {v.x(), -v.y(), -v.z()}; }

// Device samples -> body FLU / ENU measurements, with a fixed mounting and declination.
class FrameConverter
{
public:
    // r_body_sensor: the sensor's FLU axes in the body frame (identity when the unit is
    // mounted aligned, connector aft, base down).
    explicit FrameConverter(const Eigen::Matrix3d& r_body_sensor = Eigen::Matrix3d::Identity(),
                            double declination_rad = 0);
    Measurement convert(const DeviceSample& s) const;

private:
    Eigen::Matrix3d r_body_sensor_;
    double declination_rad_;
};

}  // namespace ugv::microstrain_gx1
