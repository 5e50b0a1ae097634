#include "terrain_config.hpp"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "ugv/runtime/stamp_gate.hpp"

namespace ugv::terrain_daemon {

TerrainConfig read_config(runtime::Config& cfg)
{
    TerrainConfig c;
    c.points_channel = cfg.get_channel_regex("points_channel", c.points_channel);
    c.pose_channel = cfg.get_channel_regex("pose_channel", c.pose_channel);
    c.map_channel = cfg.get_channel("map_channel", c.map_channel);
    c.publish_hz = cfg.get_double("publish_hz", 2.0, 0.1, 20.0);
    // ugv-pose publishes after each IMU sample; with the IMU silent, at each GPS input (~0.35 s
    // behind at worst). Waiting longer only holds clouds back once the poses have stopped.
    c.max_point_wait_us = static_cast<int64_t>(std::llround(cfg.get_double("max_point_wait_s", 0.5, 0.0, 5.0) * 1e6));
    c.health_timeout_us = static_cast<int64_t>(std::llround(cfg.get_double("health_timeout_s", 2.0, 0.1, 60.0) * 1e6));
    // Under systemd, StateDirectory= gives a writable folder (STATE_DIRECTORY, the first of a
    // colon-separated list); elsewhere the map is kept only when a path is configured.
    std::string default_map_file;
    if (const char* dir = std::getenv("STATE_DIRECTORY"); dir && *dir) {
        const std::string first(dir, std::strcspn(dir, ":"));
        default_map_file = first + "/terrain_map.bin";
    }
    c.map_file = cfg.get_string("map_file", default_map_file);
    c.map_save_period_us =
        static_cast<int64_t>(std::llround(cfg.get_double("map_save_period_s", 10.0, 1.0, 3600.0) * 1e6));
    c.max_stamp_ahead_us = runtime::read_max_stamp_ahead_us(cfg);
    c.stamp_skew = runtime::read_stamp_skew_limits(cfg, c.max_stamp_ahead_us);

    terrain::MapConfig& m = c.map;
    m.grid_size_m = cfg.get_double("grid_size_m", 0.2, 0.05, 2.0);
    m.extent_x_m = cfg.get_double("extent_x_m", 30.0, 1.0, 200.0);
    m.extent_y_m = cfg.get_double("extent_y_m", 30.0, 1.0, 200.0);
    m.theta_d_rad = cfg.get_double("theta_d_deg", 5.0, 0.5, 45.0) * M_PI / 180.0;
    m.statistics = cfg.get_enum("statistics", "variance_weighted", {"variance_weighted", "classical"}) == "classical"
                       ? terrain::StatisticsKind::classical
                       : terrain::StatisticsKind::variance_weighted;
    m.mode = cfg.get_enum("mode", "egocentric", {"egocentric", "world_aligned"}) == "world_aligned"
                 ? terrain::MapMode::world_aligned
                 : terrain::MapMode::egocentric;
    const std::string reference =
        cfg.get_enum("reference_point", "rear_bumper", {"rear_bumper", "rear_axle", "front_bumper", "custom"});
    const double rear_bumper_x = cfg.get_double("rear_bumper_x_m", -0.5, -10.0, 0.0);
    const double front_bumper_x = cfg.get_double("front_bumper_x_m", 2.0, 0.0, 10.0);
    const double custom_x = cfg.get_double("reference_x_m", 0.0, -10.0, 10.0);
    const double custom_y = cfg.get_double("reference_y_m", 0.0, -10.0, 10.0);
    if (reference == "rear_bumper") m.reference_x_m = rear_bumper_x;
    if (reference == "rear_axle") m.reference_x_m = 0.0;
    if (reference == "front_bumper") m.reference_x_m = front_bumper_x;
    if (reference == "custom") {
        m.reference_x_m = custom_x;
        m.reference_y_m = custom_y;
    } else if (cfg.has("reference_x_m") || cfg.has("reference_y_m")) {
        cfg.fail("reference_x_m", "only used with reference_point = \"custom\"");
    }
    m.spread = cfg.get_bool("spread", true);
    m.spread_max_cells = static_cast<int>(cfg.get_int("spread_max_cells", 2, 1, terrain::kMaxSpreadCells));
    const std::string form = cfg.get_enum("spread_form", "summed_area", {"exact", "summed_area", "centred"});
    m.spread_form = form == "exact" ? terrain::SpreadForm::exact
                    : form == "centred" ? terrain::SpreadForm::centred
                                        : terrain::SpreadForm::summed_area;
    // The older key: true is the reference; with another spread_form given, which one was
    // meant is unclear, so it is refused rather than one silently overriding the other.
    if (cfg.get_bool("spread_exact", false)) {
        if (cfg.has("spread_form") && form != "exact")
            cfg.fail("spread_exact", "true conflicts with spread_form = \"" + form + "\" (drop one of them)");
        m.spread_form = terrain::SpreadForm::exact;
    }
    m.min_variance_m2 = cfg.get_double("min_variance_m2", 1e-6, 1e-12, 1.0);
    m.pose_history_us = static_cast<int64_t>(std::llround(cfg.get_double("pose_history_s", 2.0, 0.1, 60.0) * 1e6));
    m.max_interpolation_span_s = cfg.get_double("max_interpolation_span_s", 0.1, 0.001, 1.0);
    if (static_cast<double>(m.nx()) * m.ny() > 1.0e6) cfg.fail("extent_x_m", "more than 1 million cells");
    try {
        m.validate();
    } catch (const std::invalid_argument& e) {
        cfg.fail("-", e.what());
    }
    return c;
}

}  // namespace ugv::terrain_daemon
