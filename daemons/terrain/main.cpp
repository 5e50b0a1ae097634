// ugv-terrain: POINTS.* + POSE -> TERRAIN_MAP (the report's variance-weighted, wrappable,
// rotating terrain map). Fuses at sensor rate, publishes at publish_hz of message time.
#include <spdlog/spdlog.h>

#include "terrain_config.hpp"
#include "terrain_node.hpp"
#include "ugv/bus/typed.hpp"
#include "ugv/daemon/daemon.hpp"
#include "ugv/io/clock.hpp"
#include "ugv/terrain/simd.hpp"

using namespace ugv;

int main(int argc, char** argv)
{
    daemon::Daemon d({.name = "ugv-terrain", .status_channel = "STATUS_TERRAIN", .processing = true, .bus_batch_ms = 50}, argc, argv);
    const terrain_daemon::TerrainDaemonConfig cfg = terrain_daemon::read_config(d.config());
    d.start();
    d.set_health_timeout_us(cfg.health_timeout_us);

    auto& c = d.counters();
    const char* names[] = {"points_fused",         "points_spread",         "rejected_non_finite",
                           "rejected_before_history", "rejected_after_history", "rejected_no_pose",
                           "rejected_outside_map", "poses_in",              "poses_rejected_non_finite",
                           "poses_rejected_out_of_order", "poses_rejected_status", "clouds_in",
                           "clouds_malformed",     "clouds_duplicate",      "clouds_rejected_time", "poses_rejected_time",      "wraps",                 "rotations",
                           "recentres",            "resets",                "maps_published",
                           "publish_time_us"};
    for (const char* n : names) c[n] = 0;

    terrain_daemon::TerrainNode node(
        cfg,
        [&d, &cfg](const terrain_map_t& msg) {
            bus::publish(d.out(), cfg.map_channel, msg);
            d.mark_alive();
            d.ready();
        },
        [] { return io::monotonic_us(); });
    const auto sync_counters = [&] {
        const auto& m = node.mapper().counters();
        const auto& n = node.counters();
        c["points_fused"] = static_cast<int64_t>(m.points_fused);
        c["points_spread"] = static_cast<int64_t>(m.points_spread);
        c["rejected_non_finite"] = static_cast<int64_t>(m.rejected_non_finite);
        c["rejected_before_history"] = static_cast<int64_t>(m.rejected_before_history);
        c["rejected_after_history"] = static_cast<int64_t>(m.rejected_after_history);
        c["rejected_no_pose"] = static_cast<int64_t>(m.rejected_no_pose);
        c["rejected_outside_map"] = static_cast<int64_t>(m.rejected_outside_map);
        c["poses_in"] = static_cast<int64_t>(n.poses_in);
        c["poses_rejected_non_finite"] = static_cast<int64_t>(m.poses_rejected_non_finite);
        c["poses_rejected_out_of_order"] = static_cast<int64_t>(m.poses_rejected_out_of_order);
        c["poses_rejected_status"] = static_cast<int64_t>(n.poses_rejected_status);
        c["clouds_in"] = static_cast<int64_t>(n.clouds_in);
        c["clouds_malformed"] = static_cast<int64_t>(n.clouds_malformed);
        c["clouds_duplicate"] = static_cast<int64_t>(n.clouds_duplicate);
        c["clouds_rejected_time"] = static_cast<int64_t>(n.clouds_rejected_time);
        c["poses_rejected_time"] = static_cast<int64_t>(n.poses_rejected_time);
        c["wraps"] = static_cast<int64_t>(m.wraps);
        c["rotations"] = static_cast<int64_t>(m.rotations);
        c["recentres"] = static_cast<int64_t>(m.recentres);
        c["resets"] = static_cast<int64_t>(m.resets);
        c["maps_published"] = static_cast<int64_t>(n.maps_published);
        c["publish_time_us"] = n.last_publish_us;
    };
    bus::subscribe<pose_t>(d.bus(), cfg.pose_channel, [&](const std::string&, const pose_t& m, int64_t) {
        node.on_pose(m);
        sync_counters();
    });
    bus::subscribe<point_cloud_t>(d.bus(), cfg.points_channel,
                                  [&](const std::string&, const point_cloud_t& m, int64_t) {
                                      node.on_points(m);
                                      sync_counters();
                                  });
    spdlog::info("mapping {} + {} -> {} at {} Hz of message time ({} vector code)", cfg.points_channel,
                 cfg.pose_channel, cfg.map_channel, cfg.publish_hz, ugv::terrain::to_string(ugv::terrain::simd_level()));
    const int rc = d.run();
    sync_counters();
    spdlog::info("{} points fused, {} maps published, {} wraps, {} rotations", c.get("points_fused"),
                 c.get("maps_published"), c.get("wraps"), c.get("rotations"));
    return rc;
}
