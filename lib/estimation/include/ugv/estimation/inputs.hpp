// The estimator's inputs: plain structs filled by an adapter (the ugv-pose daemon converts
// gps_fix_t, gps_velocity_t and imu_t into these). Units SI; angles rad unless named _deg;
// utime is the measurement time in us since the Unix epoch. NaN = unknown.
#pragma once

#include <cstdint>
#include <limits>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ugv::estimation {

// The receiver's fix quality (same numbering as gps_fix_t.QUALITY_*).
enum class FixQuality : int8_t {
    none = 0,
    single = 1,
    sbas = 2,
    dgps = 3,
    rtk_float = 4,
    rtk_fixed = 5,
    dead_reckoning = 6,
    unknown = 7,
};

// How good a quality is for positioning: 0 = unusable (none, dead reckoning, unknown),
// then single < sbas < dgps < rtk_float < rtk_fixed.
int quality_rank(FixQuality q);

struct GpsFix
{
    int64_t utime = 0;
    double latitude_deg = std::numeric_limits<double>::quiet_NaN();
    double longitude_deg = std::numeric_limits<double>::quiet_NaN();
    double height_m = std::numeric_limits<double>::quiet_NaN();  // ellipsoidal
    // 1-sigma (m) north, east, up as the receiver reports them; NaN = not reported (the
    // estimator then uses its configured default).
    double sigma_north_m = std::numeric_limits<double>::quiet_NaN();
    double sigma_east_m = std::numeric_limits<double>::quiet_NaN();
    double sigma_up_m = std::numeric_limits<double>::quiet_NaN();
    FixQuality quality = FixQuality::none;
};

struct GpsVelocity
{
    int64_t utime = 0;
    double horizontal_speed_mps = std::numeric_limits<double>::quiet_NaN();
    double track_rad = std::numeric_limits<double>::quiet_NaN();  // clockwise from true north
    double vertical_speed_mps = std::numeric_limits<double>::quiet_NaN();  // up positive; NaN = not reported
};

struct ImuSample
{
    int64_t utime = 0;
    bool has_orientation = false;
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // body -> ENU (magnetic yaw)
    bool has_rate = false;
    Eigen::Vector3d rate_rps = Eigen::Vector3d::Zero();  // body frame
    bool has_accel = false;
    Eigen::Vector3d accel_mps2 = Eigen::Vector3d::Zero();  // body frame specific force (gravity included)
    // 1-sigma of roll, pitch and yaw (rad); NaN = use the configured default.
    double orientation_sigma_rad = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace ugv::estimation
