#include "ugv/nodscan/nod_profile.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace ugv::nodscan {
namespace {

// A triangle wave on [0, span] at unit speed: position s along the 2*span cycle -> (value,
// direction +1 rising / -1 falling).
std::pair<double, double> triangle(double s, double span)
{
    const double cycle = 2.0 * span;
    double m = std::fmod(s, cycle);
    if (m < 0) m += cycle;
    return m <= span ? std::make_pair(m, 1.0) : std::make_pair(cycle - m, -1.0);
}

bool finite(double v) { return std::isfinite(v); }

}  // namespace

const char* to_string(NodKind k)
{
    switch (k) {
    case NodKind::stop: return "STOP";
    case NodKind::hold: return "HOLD";
    case NodKind::constant_rate: return "CONSTANT_RATE";
    case NodKind::uniform_ground_spacing: return "UNIFORM_GROUND_SPACING";
    }
    return "?";
}

double ground_distance(double h, double tilt)
{
    if (!(tilt > 0.0)) return std::numeric_limits<double>::infinity();
    return h / std::tan(tilt);
}

std::optional<std::string> validate(const NodCommand& c, const TiltLimits& hard)
{
    const auto deg = [](double r) { return std::to_string(r * 180.0 / std::numbers::pi) + " deg"; };
    switch (c.kind) {
    case NodKind::stop: return std::nullopt;
    case NodKind::hold:
        if (!finite(c.hold_angle_rad) || !hard.contains(c.hold_angle_rad))
            return "hold angle " + deg(c.hold_angle_rad) + " outside the tilt limits [" + deg(hard.min_rad) + ", " +
                   deg(hard.max_rad) + "]";
        return std::nullopt;
    case NodKind::constant_rate:
    case NodKind::uniform_ground_spacing: break;
    }
    if (!finite(c.min_tilt_rad) || !finite(c.max_tilt_rad) || !hard.contains(c.min_tilt_rad) ||
        !hard.contains(c.max_tilt_rad))
        return "nod range [" + deg(c.min_tilt_rad) + ", " + deg(c.max_tilt_rad) + "] outside the tilt limits [" +
               deg(hard.min_rad) + ", " + deg(hard.max_rad) + "]";
    if (!(c.max_tilt_rad > c.min_tilt_rad)) return "nod range is empty (max tilt must exceed min tilt)";
    if (c.kind == NodKind::constant_rate) {
        if (!finite(c.rate_rad_s) || !(c.rate_rad_s > 0.0)) return "rate must be positive";
        return std::nullopt;
    }
    if (!finite(c.ground_spacing_m) || !(c.ground_spacing_m > 0.0)) return "ground spacing must be positive";
    if (!finite(c.sensor_height_m) || !(c.sensor_height_m > 0.0)) return "sensor height must be positive";
    if (!finite(c.scan_period_s) || !(c.scan_period_s > 0.0)) return "scan period must be positive";
    if (!(c.min_tilt_rad > 0.0))
        return "uniform ground spacing needs the whole nod range below horizontal (min tilt > 0)";
    return std::nullopt;
}

void NodProfile::start(const NodCommand& c, double t0_s, double current)
{
    command_ = c;
    t0_s_ = t0_s;
    hold_rad_ = c.kind == NodKind::hold ? c.hold_angle_rad : current;
    const double a = std::clamp(current, c.min_tilt_rad, c.max_tilt_rad);
    if (c.kind == NodKind::constant_rate) {
        phase0_ = a - c.min_tilt_rad;  // rising part of the triangle: towards max tilt
    } else if (c.kind == NodKind::uniform_ground_spacing) {
        // Travel is measured in ground distance from the far end (min tilt): rising tilt = the
        // hit point coming nearer.
        const double far = ground_distance(c.sensor_height_m, c.min_tilt_rad);
        phase0_ = far - ground_distance(c.sensor_height_m, a);
    }
}

TiltSetpoint NodProfile::at(double t) const
{
    const double dt = std::max(0.0, t - t0_s_);
    const NodCommand& c = command_;
    switch (c.kind) {
    case NodKind::stop:
    case NodKind::hold: return {hold_rad_, 0.0};
    case NodKind::constant_rate: {
        const auto [s, dir] = triangle(phase0_ + c.rate_rad_s * dt, c.max_tilt_rad - c.min_tilt_rad);
        return {std::clamp(c.min_tilt_rad + s, c.min_tilt_rad, c.max_tilt_rad), dir * c.rate_rad_s};
    }
    case NodKind::uniform_ground_spacing: {
        const double h = c.sensor_height_m;
        const double far = ground_distance(h, c.min_tilt_rad);
        const double near = ground_distance(h, c.max_tilt_rad);
        const double ground_speed = c.ground_spacing_m / c.scan_period_s;  // m/s of the hit point
        const auto [s, dir] = triangle(phase0_ + ground_speed * dt, far - near);
        const double d = far - s;
        const double angle = std::clamp(std::atan2(h, d), c.min_tilt_rad, c.max_tilt_rad);
        const double sin_a = std::sin(angle);
        // d decreases while s rises, and the tilt grows: dtheta/dt = v sin^2(theta) / h.
        return {angle, dir * ground_speed * sin_a * sin_a / h};
    }
    }
    return {hold_rad_, 0.0};
}

double NodProfile::nod_period_s() const
{
    const NodCommand& c = command_;
    if (c.kind == NodKind::constant_rate) return 2.0 * (c.max_tilt_rad - c.min_tilt_rad) / c.rate_rad_s;
    if (c.kind == NodKind::uniform_ground_spacing) {
        const double span = ground_distance(c.sensor_height_m, c.min_tilt_rad) -
                            ground_distance(c.sensor_height_m, c.max_tilt_rad);
        return 2.0 * span * c.scan_period_s / c.ground_spacing_m;
    }
    return 0.0;
}

}  // namespace ugv::nodscan
