#include "nod_controller.hpp"

#include <algorithm>
#include <cmath>

namespace ugv::servo_daemon {

NodController::NodController(NodControllerOptions options) : options_(options) {}

std::optional<std::string> NodController::apply(const nodscan::NodCommand& command, double t_s, double current)
{
    if (auto why = nodscan::validate(command, options_.hard_limits)) return why;
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
