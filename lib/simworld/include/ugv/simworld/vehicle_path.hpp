// The vehicle's planned motion on the ground plane: straight and arc segments and stops,
// driven with a bounded acceleration. Sampled once at 1 ms when built, so the truth at any
// time is an interpolation (every device sees the same motion, whatever order it asks in).
#pragma once

#include <vector>

namespace ugv::simworld {

struct PathSegment
{
    enum class Kind { straight, arc, stop };
    Kind kind = Kind::stop;
    double length_m = 0.0;    // straight
    double radius_m = 0.0;    // arc, > 0
    double turn_rad = 0.0;    // arc: heading change, + = left (counter-clockwise)
    double speed_mps = 0.0;   // straight, arc: the speed to drive at (<= 3 m/s for the report's vehicle)
    double duration_s = 0.0;  // stop: how long to stand (after braking)
};

struct PathSpec
{
    double x0_m = 0.0, y0_m = 0.0;  // start of the reference point, world ENU
    double yaw0_rad = 0.0;          // ENU yaw: 0 = east, counter-clockwise positive
    double accel_mps2 = 1.0;        // speed changes at this rate
    std::vector<PathSegment> segments;
};

// The planar motion at one time (world ENU, reference point on the ground).
struct PlanarState
{
    double x_m = 0, y_m = 0, yaw_rad = 0;
    double speed_mps = 0;        // along the heading (>= 0)
    double yaw_rate_radps = 0;
    double accel_along_mps2 = 0; // d(speed)/dt
};

class VehiclePath
{
public:
    explicit VehiclePath(const PathSpec& spec);
    // Clamped to [0, duration_s()].
    PlanarState at(double t_s) const;
    double duration_s() const { return static_cast<double>(samples_.size() - 1) * kStepS; }
    double length_m() const { return length_m_; }

    static constexpr double kStepS = 0.001;

private:
    std::vector<PlanarState> samples_;
    double length_m_ = 0.0;
};

}  // namespace ugv::simworld
