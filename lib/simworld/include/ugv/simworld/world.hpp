// The simulated vehicle in its world: the truth of the vehicle at any time (the path on the
// terrain, with the attitude the wheels give it), and what each sensor would measure of it
// without noise. One World is shared by every emulated device, so they all agree.
#pragma once

#include <cstddef>
#include <cstdint>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "ugv/simworld/height_field.hpp"
#include "ugv/simworld/scenario.hpp"
#include "ugv/simworld/vehicle_path.hpp"

namespace ugv::simworld {

struct TruthState
{
    int64_t utime = 0;
    Eigen::Vector3d position_m = Eigen::Vector3d::Zero();  // reference point, world ENU
    Eigen::Vector3d velocity_mps = Eigen::Vector3d::Zero();
    Eigen::Vector3d accel_mps2 = Eigen::Vector3d::Zero();  // kinematic (gravity not included)
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // body -> ENU
    double roll_rad = 0, pitch_rad = 0, yaw_rad = 0;  // Rz(yaw) Ry(pitch) Rx(roll); pitch + = nose down
    Eigen::Vector3d rate_body_radps = Eigen::Vector3d::Zero();
    double yaw_rate_radps = 0;  // the path's turn rate (ENU, counter-clockwise positive)
};

struct Geodetic
{
    double latitude_deg, longitude_deg, height_m;  // ellipsoidal height
};

class World
{
public:
    // The scenario's path starts at start_utime.
    World(const Scenario& scenario, int64_t start_utime);

    TruthState truth(int64_t utime) const;
    // The range along one beam of scenario().lasers[laser] (no noise), +infinity for no echo
    // within max_range_m.
    double beam_range_m(const TruthState& state, double tilt_rad, double beam_angle_rad, double max_range_m,
                        std::size_t laser = 0) const;
    // The GPS antenna's position (the scenario's true antenna_m).
    Geodetic antenna_position(const TruthState& state) const;
    // Its ENU velocity: the reference point's plus the turn's (yaw rate x lever arm). The roll
    // and pitch rates are left out: on the raster terrain they are its staircase, not motion.
    Eigen::Vector3d antenna_velocity(const TruthState& state) const;
    Geodetic to_geodetic(const Eigen::Vector3d& enu_m) const;

    const HeightField& field() const { return field_; }
    const Scenario& scenario() const { return scenario_; }
    int64_t start_utime() const { return start_utime_; }
    // The path's end plus the hold time.
    int64_t end_utime() const;

private:
    double ground_at(double x_m, double y_m) const;
    // Position and attitude on the terrain, without rates.
    void place(const PlanarState& p, TruthState& s) const;

    Scenario scenario_;
    int64_t start_utime_;
    VehiclePath path_;
    HeightField field_;
};

}  // namespace ugv::simworld
