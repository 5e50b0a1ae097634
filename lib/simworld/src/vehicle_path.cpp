#include "ugv/simworld/vehicle_path.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ugv::simworld {

namespace {

constexpr double kPi = 3.14159265358979323846;

double wrap(double a)
{
    return std::remainder(a, 2.0 * kPi);
}

}  // namespace

VehiclePath::VehiclePath(const PathSpec& spec)
{
    if (!(spec.accel_mps2 > 0)) throw std::invalid_argument("path: accel_mps2 must be > 0");
    const double dt = kStepS;
    PlanarState s;
    s.x_m = spec.x0_m;
    s.y_m = spec.y0_m;
    s.yaw_rad = wrap(spec.yaw0_rad);
    samples_.push_back(s);
    auto step = [&](double target_speed, double curvature) {
        const double dv = std::clamp(target_speed - s.speed_mps, -spec.accel_mps2 * dt, spec.accel_mps2 * dt);
        const double v0 = s.speed_mps, v1 = v0 + dv;
        const double ds = 0.5 * (v0 + v1) * dt;  // exact for constant acceleration
        const double dyaw = curvature * ds;
        // Midpoint heading: second-order accurate on arcs.
        const double mid = s.yaw_rad + 0.5 * dyaw;
        s.x_m += ds * std::cos(mid);
        s.y_m += ds * std::sin(mid);
        s.yaw_rad = wrap(s.yaw_rad + dyaw);
        s.speed_mps = v1;
        s.accel_along_mps2 = dv / dt;
        s.yaw_rate_radps = curvature * 0.5 * (v0 + v1);
        length_m_ += ds;
        samples_.push_back(s);
        return ds;
    };
    for (const PathSegment& seg : spec.segments) {
        switch (seg.kind) {
        case PathSegment::Kind::straight:
        case PathSegment::Kind::arc: {
            if (!(seg.speed_mps > 0)) throw std::invalid_argument("path: a moving segment needs speed_mps > 0");
            const bool arc = seg.kind == PathSegment::Kind::arc;
            if (arc && !(seg.radius_m > 0)) throw std::invalid_argument("path: an arc needs radius_m > 0");
            const double length = arc ? seg.radius_m * std::abs(seg.turn_rad) : seg.length_m;
            const double curvature = arc ? std::copysign(1.0 / seg.radius_m, seg.turn_rad) : 0.0;
            double done = 0.0;
            while (done < length) done += step(seg.speed_mps, curvature);
            break;
        }
        case PathSegment::Kind::stop: {
            while (s.speed_mps > 0) step(0.0, 0.0);
            for (double t = 0; t < seg.duration_s; t += dt) step(0.0, 0.0);
            break;
        }
        }
    }
    // Come to rest at the end of the path.
    while (s.speed_mps > 0) step(0.0, 0.0);
    s.accel_along_mps2 = 0;
    s.yaw_rate_radps = 0;
    samples_.push_back(s);
}

PlanarState VehiclePath::at(double t_s) const
{
    const double k = std::clamp(t_s / kStepS, 0.0, static_cast<double>(samples_.size() - 1));
    const auto i = std::min(static_cast<std::size_t>(k), samples_.size() - 2);
    const double f = k - static_cast<double>(i);
    const PlanarState& a = samples_[i];
    const PlanarState& b = samples_[i + 1];
    PlanarState r = b;  // rates and acceleration of the step ending at b
    r.x_m = a.x_m + f * (b.x_m - a.x_m);
    r.y_m = a.y_m + f * (b.y_m - a.y_m);
    r.yaw_rad = wrap(a.yaw_rad + f * wrap(b.yaw_rad - a.yaw_rad));
    r.speed_mps = a.speed_mps + f * (b.speed_mps - a.speed_mps);
    return r;
}

}  // namespace ugv::simworld
