#include "ugv/microstrain_gx1/sample_plausibility.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace ugv::microstrain_gx1 {

namespace {

constexpr double kPi = 3.14159265358979323846;
// Euler angles carry the unit's own sample-to-sample noise: the 3DM-GX1 model of the
// simulator has 0.7 deg per sample, the older 3DM-G's +/-5 deg more. A bound of 0.01 rad
// refused half of the simulator's samples; 20 deg passes that noise and still catches the
// gross errors a cancelling pair of flips in a high bit makes.
constexpr double kAngleNoiseSlackRad = 0.35;

double norm3(const std::array<double, 3>& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }

bool steps_within(const std::array<double, 3>& a, const std::array<double, 3>& b, double bound)
{
    for (int k = 0; k < 3; ++k)
        if (!(std::fabs(b[k] - a[k]) <= bound)) return false;  // NaN fails too
    return true;
}

double angle_step(double a, double b) { return std::fabs(std::remainder(b - a, 2 * kPi)); }

}  // namespace

void SamplePlausibility::reset()
{
    last_taken_.reset();
    previous_.reset();
    holding_ = false;
}

bool SamplePlausibility::agree(const DeviceSample& a, const DeviceSample& b, double tick_period_s) const
{
    double dt = 0.0;
    if (a.has_ticks && b.has_ticks) {
        const int step = static_cast<uint16_t>(b.ticks - a.ticks);  // the u16 timer wraps
        dt = step * tick_period_s;
        if (step == 0 || dt > 1.0) return false;
    }
    if (a.has_rate && b.has_rate && !steps_within(a.rate_radps, b.rate_radps, 50.0 * dt + 0.5)) return false;
    if (a.has_accel && b.has_accel && !steps_within(a.accel_mps2, b.accel_mps2, 300.0 * dt + 20.0)) return false;
    if (a.has_mag && b.has_mag && !steps_within(a.mag_gauss, b.mag_gauss, 2.0 * dt + 0.2)) return false;
    if (a.has_euler && b.has_euler) {
        const double rate = a.has_rate && b.has_rate ? std::max(norm3(a.rate_radps), norm3(b.rate_radps)) : 5.3;
        const double bound = (1.5 * rate + 0.2) * dt + kAngleNoiseSlackRad;
        if (!(angle_step(a.roll_rad, b.roll_rad) <= bound && angle_step(a.pitch_rad, b.pitch_rad) <= bound &&
              angle_step(a.yaw_rad, b.yaw_rad) <= bound))
            return false;
    }
    return true;
}

bool SamplePlausibility::check(const DeviceSample& s, double tick_period_s)
{
    const std::optional<DeviceSample> previous = std::exchange(previous_, s);
    const bool previous_held = std::exchange(holding_, false);
    if (last_taken_ && agree(*last_taken_, s, tick_period_s)) {
        if (previous_held) ++implausible_;  // the one in between was damaged
        last_taken_ = s;
        return true;
    }
    if (previous && agree(*previous, s, tick_period_s)) {  // two in a row: a real change
        last_taken_ = s;
        return true;
    }
    if (previous_held) ++implausible_;
    holding_ = true;
    return false;
}

}  // namespace ugv::microstrain_gx1
