#include "position_error.hpp"

#include <cmath>

#include "ugv/novatel/fix_quality.hpp"

namespace ugv::sim::gps {

namespace nv = ugv::novatel;

FixClass fix_class_of(uint32_t type)
{
    switch (nv::quality_from_position_type(0, type)) {
    case nv::FixQuality::rtk_fixed: return FixClass::rtk_fixed;
    case nv::FixQuality::rtk_float: return FixClass::rtk_float;
    case nv::FixQuality::dgps: return FixClass::dgps;
    case nv::FixQuality::sbas: return FixClass::sbas;
    case nv::FixQuality::single: return FixClass::single;
    default: return FixClass::other;
    }
}

const char* fix_class_name(FixClass c)
{
    switch (c) {
    case FixClass::rtk_fixed: return "rtk_fixed";
    case FixClass::rtk_float: return "rtk_float";
    case FixClass::dgps: return "dgps";
    case FixClass::sbas: return "sbas";
    case FixClass::single: return "single";
    case FixClass::other: break;
    }
    return "other";
}

PositionErrorModel::PositionErrorModel(const PositionErrorConfig& config) : config_(config), rng_(config.seed) {}

double PositionErrorModel::sigma_horizontal_m(uint32_t type) const
{
    return config_.classes[static_cast<std::size_t>(fix_class_of(type))].sigma_m * config_.scale;
}

Ned3 PositionErrorModel::at(int64_t utime, uint32_t type)
{
    const std::size_t c = static_cast<std::size_t>(fix_class_of(type));
    Process& p = processes_[c];
    if (!p.started) {
        // A class never used before starts anywhere in its stationary spread.
        for (int i = 0; i < 3; ++i) p.error[i] = gauss_(rng_);
        p.started = true;
    } else if (utime > p.utime) {
        // Exact discretisation over any gap: x <- a x + sqrt(1 - a^2) w keeps unit variance.
        const double a = std::exp(-static_cast<double>(utime - p.utime) * 1e-6 / config_.classes[c].time_constant_s);
        const double b = std::sqrt(1.0 - a * a);
        for (int i = 0; i < 3; ++i) p.error[i] = a * p.error[i] + b * gauss_(rng_);
    }
    if (utime > p.utime) p.utime = utime;
    const double s = sigma_horizontal_m(type);
    return {s * p.error[0], s * p.error[1], 1.5 * s * p.error[2]};
}

}  // namespace ugv::sim::gps
