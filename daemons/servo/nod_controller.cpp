#include "nod_controller.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace ugv::servo_daemon {

namespace {

std::string num(double v)
{
    char b[32];
    std::snprintf(b, sizeof b, "%g", v);
    return b;
}

double deg(double rad) { return rad * 180.0 / std::numbers::pi; }

}  // namespace

std::optional<std::string> check_command(const nodscan::NodCommand& c, const NodControllerOptions& o)
{
    switch (c.kind) {
    case nodscan::NodKind::stop:
    case nodscan::NodKind::hold:
    case nodscan::NodKind::constant_rate:
    case nodscan::NodKind::uniform_ground_spacing: break;
    default: return "unknown profile " + std::to_string(static_cast<int>(c.kind));
    }
    if (auto why = nodscan::validate(c, o.hard_limits)) return why;
    if (c.kind == nodscan::NodKind::constant_rate && c.rate_rad_s > o.max_rate_rad_s)
        return "rate " + num(c.rate_rad_s) + " rad/s (" + num(deg(c.rate_rad_s)) + " deg/s) is above max_rate_deg_s = " +
               num(deg(o.max_rate_rad_s));
    if (c.kind == nodscan::NodKind::uniform_ground_spacing) {
        if (c.ground_spacing_m < o.min_ground_spacing_m || c.ground_spacing_m > o.max_ground_spacing_m)
            return "ground spacing " + num(c.ground_spacing_m) + " m is outside [" + num(o.min_ground_spacing_m) + ", " +
                   num(o.max_ground_spacing_m) + "] m";
        if (c.sensor_height_m < o.min_sensor_height_m || c.sensor_height_m > o.max_sensor_height_m)
            return "sensor height " + num(c.sensor_height_m) + " m is outside [" + num(o.min_sensor_height_m) + ", " +
                   num(o.max_sensor_height_m) + "] m";
    }
    if (c.kind == nodscan::NodKind::constant_rate || c.kind == nodscan::NodKind::uniform_ground_spacing) {
        nodscan::NodProfile p;
        p.start(c, 0.0, c.min_tilt_rad);
        const double period = p.nod_period_s();
        if (!(period <= o.max_nod_period_s))  // also NaN and inf
            return "one nod would take " + num(period) + " s, more than max_nod_period_s (" + num(o.max_nod_period_s) + ")";
    }
    return std::nullopt;
}

NodController::NodController(NodControllerOptions options) : options_(options) {}

std::optional<std::string> NodController::apply(const nodscan::NodCommand& command, double t_s, double current)
{
    if (auto why = check_command(command, options_)) return why;
    const double from = std::clamp(current, options_.hard_limits.min_rad, options_.hard_limits.max_rad);
    profile_.start(command, t_s, from);
    started_ = true;
    return std::nullopt;
}

void NodController::resume(double t_s, double current)
{
    if (!started_) return;
    const double from = std::clamp(current, options_.hard_limits.min_rad, options_.hard_limits.max_rad);
    profile_.start(profile_.command(), t_s, from);
}

NodController::Output NodController::update(double t_s, double current) const
{
    const nodscan::TiltSetpoint sp = profile_.at(t_s + options_.lead_s);
    Output o;
    // The profile stays within its validated range; clamp again as the last guard.
    o.angle_rad = std::clamp(sp.angle_rad, options_.hard_limits.min_rad, options_.hard_limits.max_rad);
    const auto k = profile_.command().kind;
    if (k == nodscan::NodKind::stop || k == nodscan::NodKind::hold) {
        o.speed_rad_s = options_.hold_speed_rad_s;
    } else {
        // The lag behind where the profile is now (not the led set-point): zero when tracking.
        const double lag = std::isfinite(current) ? std::fabs(profile_.at(t_s).angle_rad - current) : 0.0;
        o.speed_rad_s = std::max(options_.min_speed_rad_s,
                                 options_.speed_margin * std::fabs(sp.velocity_rad_s) + lag / options_.catch_up_s);
    }
    return o;
}

}  // namespace ugv::servo_daemon
