#include "ugv/simworld/world.hpp"

#include <algorithm>
#include <cmath>

#include <GeographicLib/LocalCartesian.hpp>

#include "ugv/geometry/rotation.hpp"

namespace ugv::simworld {

namespace {

// The ground the path covers, with the margin.
Rect path_area(const VehiclePath& path, double margin_m)
{
    Rect r{1e300, 1e300, -1e300, -1e300};
    for (double t = 0; t <= path.duration_s(); t += 0.05) {
        const PlanarState s = path.at(t);
        r.x0_m = std::min(r.x0_m, s.x_m);
        r.y0_m = std::min(r.y0_m, s.y_m);
        r.x1_m = std::max(r.x1_m, s.x_m);
        r.y1_m = std::max(r.y1_m, s.y_m);
    }
    return {r.x0_m - margin_m, r.y0_m - margin_m, r.x1_m + margin_m, r.y1_m + margin_m};
}

}  // namespace

World::World(const Scenario& scenario, int64_t start_utime)
    : scenario_(scenario),
      start_utime_(start_utime),
      path_(scenario.path),
      field_(rasterize(scenario.terrain, path_area(path_, scenario.field_margin_m), scenario.field_resolution_m))
{
}

int64_t World::end_utime() const
{
    return start_utime_ + static_cast<int64_t>(std::llround((path_.duration_s() + scenario_.hold_s) * 1e6));
}

double World::ground_at(double x_m, double y_m) const
{
    const double z = field_.height_at(x_m, y_m);
    return std::isfinite(z) ? z : scenario_.terrain.ground_z_m;
}

void World::place(const PlanarState& p, TruthState& s) const
{
    // The four wheels on the terrain give the body's height, pitch and roll.
    const Eigen::Matrix2d turn = geometry::rotation_2d(p.yaw_rad);
    const double wb = scenario_.vehicle.wheelbase_m, half = scenario_.vehicle.track_m / 2;
    auto wheel = [&](double bx, double by) {
        const Eigen::Vector2d w = turn * Eigen::Vector2d(bx, by);
        return ground_at(p.x_m + w.x(), p.y_m + w.y());
    };
    const double rl = wheel(0, half), rr = wheel(0, -half), fl = wheel(wb, half), fr = wheel(wb, -half);
    const double rear = 0.5 * (rl + rr), front = 0.5 * (fl + fr);
    const double left = 0.5 * (rl + fl), right = 0.5 * (rr + fr);
    s.roll_rad = std::atan2(left - right, 2 * half);
    s.pitch_rad = std::atan2(rear - front, wb);
    s.yaw_rad = p.yaw_rad;
    s.position_m = {p.x_m, p.y_m, rear};
    s.orientation = geometry::quaternion_from_euler({s.roll_rad, s.pitch_rad, s.yaw_rad});
}

TruthState World::truth(int64_t utime) const
{
    const double t = static_cast<double>(utime - start_utime_) * 1e-6;
    const PlanarState p = path_.at(t);
    TruthState s;
    s.utime = utime;
    place(p, s);
    // Rates of height and attitude by central differences over 20 ms (the terrain's slopes
    // change over a column's width, so a shorter step only sees the staircase).
    constexpr double h = 0.01;
    TruthState before, after;
    place(path_.at(t - h), before);
    place(path_.at(t + h), after);
    const Eigen::Vector3d heading(std::cos(p.yaw_rad), std::sin(p.yaw_rad), 0.0);
    const Eigen::Vector3d left(-std::sin(p.yaw_rad), std::cos(p.yaw_rad), 0.0);
    s.velocity_mps = p.speed_mps * heading;
    s.velocity_mps.z() = (after.position_m.z() - before.position_m.z()) / (2 * h);
    s.accel_mps2 = p.accel_along_mps2 * heading + p.speed_mps * p.yaw_rate_radps * left;
    s.yaw_rate_radps = p.yaw_rate_radps;
    // Body rates from the two attitudes (not Euler-angle rates): a gyro integrated from them
    // follows the true attitude, as the emulated IMU's filter needs.
    const Eigen::AngleAxisd turn(before.orientation.conjugate() * after.orientation);
    s.rate_body_radps = turn.axis() * (turn.angle() / (2 * h));
    return s;
}

double World::beam_range_m(const TruthState& s, double tilt_rad, double beam_angle_rad, double max_range_m,
                           std::size_t laser) const
{
    const nodscan::MountGeometry& mount = scenario_.lasers.at(laser).mount;
    const Eigen::Vector3d origin_body = nodscan::laser_origin_body(mount, tilt_rad);
    const Eigen::Vector3d dir_body = nodscan::beam_point_body(mount, tilt_rad, beam_angle_rad, 1.0) - origin_body;
    const Eigen::Vector3d origin = s.position_m + s.orientation * origin_body;
    const Eigen::Vector3d dir = (s.orientation * dir_body).normalized();
    return ray_cast(field_, origin, dir, max_range_m);
}

Geodetic World::to_geodetic(const Eigen::Vector3d& enu) const
{
    const GeographicLib::LocalCartesian frame(scenario_.datum_latitude_deg, scenario_.datum_longitude_deg,
                                              scenario_.datum_height_m);
    Geodetic g{};
    frame.Reverse(enu.x(), enu.y(), enu.z(), g.latitude_deg, g.longitude_deg, g.height_m);
    return g;
}

Geodetic World::antenna_position(const TruthState& s) const
{
    return to_geodetic(s.position_m + s.orientation * scenario_.gps.antenna_m);
}

Eigen::Vector3d World::antenna_velocity(const TruthState& s) const
{
    return s.velocity_mps + Eigen::Vector3d(0, 0, s.yaw_rate_radps).cross(s.orientation * scenario_.gps.antenna_m);
}

}  // namespace ugv::simworld
