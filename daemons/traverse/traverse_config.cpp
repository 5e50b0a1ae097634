#include "traverse_config.hpp"

#include <cmath>
#include <stdexcept>

#include <spdlog/fmt/fmt.h>

#include "ugv/runtime/stamp_gate.hpp"

namespace ugv::traverse_daemon {

namespace {

int64_t seconds_to_us(double s)
{
    return static_cast<int64_t>(std::llround(s * 1e6));
}

}  // namespace

TraverseConfig read_config(runtime::Config& cfg)
{
    TraverseConfig c;
    c.map_channel = cfg.get_channel_regex("map_channel", c.map_channel);
    c.traversability_channel = cfg.get_channel("traversability_channel", c.traversability_channel);
    c.arcs_channel = cfg.get_channel("arcs_channel", c.arcs_channel);
    c.health_timeout_us = seconds_to_us(cfg.get_double("health_timeout_s", 2.0, 0.1, 60.0));
    c.max_stamp_ahead_us = runtime::read_max_stamp_ahead_us(cfg);
    c.stamp_skew = runtime::read_stamp_skew_limits(cfg, c.max_stamp_ahead_us);

    // The same vehicle as ugv-terrain's rear_bumper_x_m and front_bumper_x_m (body frame, from
    // the rear axle centre).
    runtime::Config fp = cfg.section("footprint");
    traverse::Footprint& f = c.analysis.footprint;
    f.rear_x_m = fp.get_double("rear_x_m", f.rear_x_m, -10.0, 0.0);
    f.front_x_m = fp.get_double("front_x_m", f.front_x_m, 0.1, 10.0);
    f.width_m = fp.get_double("width_m", f.width_m, 0.1, 10.0);

    runtime::Config cl = cfg.section("classifier");
    traverse::ClassifierConfig& k = c.analysis.classifier;
    k.max_step_m = cl.get_double("max_step_m", k.max_step_m, 0.01, 5.0);
    k.max_drop_m = cl.get_double("max_drop_m", k.max_drop_m, 0.01, 5.0);
    k.step_radius_m = cl.get_double("step_radius_m", k.step_radius_m, 0.05, 5.0);
    k.face_mean_step_m = cl.get_double("face_mean_step_m", k.face_mean_step_m, 0.001, 5.0);
    k.max_slope_deg = cl.get_double("max_slope_deg", k.max_slope_deg, 1.0, 89.0);
    k.slope_radius_m = cl.get_double("slope_radius_m", k.slope_radius_m, 0.1, 5.0);
    k.ground_radius_m = cl.get_double("ground_radius_m", k.ground_radius_m, 0.2, 20.0);
    k.shadow_radius_m = cl.get_double("shadow_radius_m", k.shadow_radius_m, 0.1, 5.0);
    k.max_roughness_m = cl.get_double("max_roughness_m", k.max_roughness_m, 0.001, 5.0);
    k.min_support_samples = cl.get_double("min_support_samples", k.min_support_samples, 1.0, 1000.0);
    k.max_age_s = cl.get_double("max_age_s", k.max_age_s, 0.1, 3600.0);
    k.max_driven_m = cl.get_double("max_driven_m", k.max_driven_m, 0.1, 10000.0);
    c.max_stamp_age_us = seconds_to_us(k.max_age_s);

    runtime::Config ar = cfg.section("arcs");
    traverse::ArcSetConfig& a = c.analysis.arcs;
    a.count = static_cast<int>(ar.get_int("count", a.count, 1, 201));
    a.max_curvature_per_m = ar.get_double("max_curvature_per_m", a.max_curvature_per_m, 0.0, 5.0);
    a.length_m = ar.get_double("length_m", a.length_m, 0.5, 100.0);
    a.margin_m = ar.get_double("margin_m", a.margin_m, 0.0, 5.0);
    a.unknown_policy = ar.get_enum("unknown_policy", "optimistic", {"optimistic", "cautious"}) == "cautious"
                           ? traverse::UnknownPolicy::cautious
                           : traverse::UnknownPolicy::optimistic;
    a.max_unknown_fraction = ar.get_double("max_unknown_fraction", a.max_unknown_fraction, 0.0, 1.0);
    a.unknown_weight = ar.get_double("unknown_weight", a.unknown_weight, 0.0, 1.0);
    // The turning centre must lie outside the swept width, or the vehicle spins in place.
    const double half_swept_m = 0.5 * f.width_m + a.margin_m;
    if (a.max_curvature_per_m * half_swept_m >= 1.0)
        ar.fail("max_curvature_per_m", "the turning radius must exceed half the swept width ([footprint] width_m / 2 + "
                                       "margin_m = " + fmt::format("{:g}", half_swept_m) + " m)");
    if (a.count > 1 && a.max_curvature_per_m == 0.0) ar.fail("max_curvature_per_m", "must be > 0 with more than one arc");

    // Whatever else the library refuses.
    try {
        traverse::Traversability check(c.analysis);
    } catch (const std::invalid_argument& e) {
        cfg.fail("-", e.what());
    }
    return c;
}

}  // namespace ugv::traverse_daemon
