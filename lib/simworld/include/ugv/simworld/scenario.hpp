// A simulation scenario: terrain, the vehicle's path, its sensors' mounts and noise, and
// which devices to emulate. Read from TOML (ugv::runtime::Config: a bad value is the one
// line `FILE: KEY: why`); default_scenario_toml() is the report's demonstration.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "ugv/nodscan/mount.hpp"
#include "ugv/runtime/config.hpp"
#include "ugv/simworld/terrain_spec.hpp"
#include "ugv/simworld/vehicle_path.hpp"

namespace ugv::simworld {

struct VehicleSpec
{
    // The body frame's origin (the reference point) is the middle of the rear axle on the
    // ground; the front axle is wheelbase_m ahead.
    double wheelbase_m = 2.5;
    double track_m = 1.6;
};

struct ServoSpec
{
    int node_id = 1;
    double counts_per_rev = 4096;  // encoder resolution, as ugv-servo's keys of that name
    double gear_ratio = 50;
    double counts_per_rad() const;
};

// One nodding laser: the LMS on its tilt axis and the servo that nods it.
struct LaserSpec
{
    // "" for the one laser of a scenario without [[laser]] tables; else the [[laser]]'s name,
    // which names its devices in the run folder (lms-NAME, servo-NAME) and its calibration.
    std::string name;
    nodscan::MountGeometry mount{{0.0, 0.0, 0.87}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};  // as ugv-nodscan's [mount]
    // What ugv-nodscan is told (the run folder's calibration/); the true mount unless the
    // scenario's configured_* keys say otherwise, so a calibration can be checked against it.
    nodscan::MountGeometry configured_mount = mount;
    double range_noise_m = 0.01;   // 1-sigma
    ServoSpec servo;
    // "" or "-NAME": appended to lms, servo and calibration/nodscan in the run folder.
    std::string suffix() const { return name.empty() ? "" : "-" + name; }
};

constexpr std::size_t kMaxLasers = 8;

// One class of position type's error under the "markov" model.
struct GpsClassError
{
    double sigma_m;          // horizontal 1-sigma per axis; height 1.5x
    double time_constant_s;  // correlation time
};

struct GpsSpec
{
    std::string protocol = "novatel";          // novatel | nmea
    std::string position_types = "NARROW_INT@0";  // the receiver's solution over time
    double noise_scale = 1.0;                  // x the position type's sigma
    Eigen::Vector3d antenna_m{0.0, 0.0, 1.8};  // body frame, true
    Eigen::Vector3d configured_antenna_m = antenna_m;  // what ugv-pose is told (gps_antenna_m)
    // "markov": each class's error a first-order Gauss-Markov process (below); "white": an
    // independent draw per fix with the fixed sigmas of the receiver emulator.
    std::string error_model = "markov";
    // rtk_fixed, rtk_float, dgps, sbas, single (scenario keys <class>_sigma_m and
    // <class>_time_constant_s); any other type uses single's time constant and 10 m.
    GpsClassError rtk_fixed{0.02, 30.0}, rtk_float{0.15, 60.0}, dgps{0.4, 60.0}, sbas{0.8, 120.0}, single{1.5, 120.0};
};

struct ImuSpec
{
    // "ahrs": the unit's complementary filter (false tilt while the vehicle accelerates or
    // turns, gyro bias walk, heading-dependent magnetometer error) plus the white noise
    // below; "white": the white noise alone, standing for the whole dynamic error.
    std::string error_model = "ahrs";
    double tilt_time_constant_s = 10.0;               // the filter's pull toward gravity and north
    double gyro_bias_walk_dps_per_sqrt_s = 0.0005;
    double mag_disturbance_deg = 1.0;                 // amplitude of the heading-dependent yaw error
    double angle_sigma_deg = 0.047;  // white, per sample: "ahrs" 0.047 (static), "white" 0.7 (+/-2 deg at 3 sigma)
    double rate_sigma_dps = 0.1;
    double accel_sigma_mps2 = 0.02;
    double declination_deg = 0.0;   // magnetic yaw = true yaw + this (the filter estimates it)
    // The unit's FLU axes in the body frame (ZYX roll, pitch, yaw, rad), as ugv-imu's
    // mount_rpy_deg: the true mounting, and the one ugv-imu is told.
    Eigen::Vector3d mount_rpy_rad = Eigen::Vector3d::Zero();
    Eigen::Vector3d configured_mount_rpy_rad = mount_rpy_rad;
};

struct DeviceSet
{
    bool lms = true, servo = true, gps = true, imu = true;
};

struct Scenario
{
    std::string name = "default";
    double datum_latitude_deg = 50.2706;   // world ENU origin
    double datum_longitude_deg = -110.7389;
    double datum_height_m = 750.0;         // ellipsoidal
    double undulation_m = -17.0;           // geoid above ellipsoid, for the receiver's MSL height
    TerrainSpec terrain;
    double field_resolution_m = 0.05;
    double field_margin_m = 30.0;          // the truth field covers the path plus this
    PathSpec path;
    double hold_s = 5.0;                   // standing still after the path before ending
    VehicleSpec vehicle;
    // At least one: [laser] and [servo] (one laser, named ""), or one per [[laser]] table.
    std::vector<LaserSpec> lasers{LaserSpec{}};
    GpsSpec gps;
    ImuSpec imu;
    DeviceSet devices;
};

// Reads every key (defaults = the built-in defaults above); calls cfg.finish().
Scenario parse_scenario(runtime::Config& cfg);
// The report's demonstration (figures 16-19): drive forward at 3 m/s past a box and a
// building wall, a left turn, and stop facing a wall.
const char* default_scenario_toml();

}  // namespace ugv::simworld
