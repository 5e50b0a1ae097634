#include "traverse_messages.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace ugv::traverse_daemon {

void to_grid(const terrain_map_t& msg, traverse::TerrainGrid& grid)
{
    grid.utime_us = msg.utime;
    grid.seq = msg.seq;
    grid.position_m = {msg.pose.position[0], msg.pose.position[1], msg.pose.position[2]};
    grid.resolution_m = msg.resolution;
    grid.nx = msg.nx;
    grid.ny = msg.ny;
    grid.origin_x_m = msg.origin_x;
    grid.origin_y_m = msg.origin_y;
    grid.residual_yaw_rad = msg.residual_yaw;
    grid.mean_z_m = msg.mean_z;
    grid.variance_z_m2 = msg.variance_z;
    grid.max_z_m = msg.max_z;
    grid.min_z_m = msg.min_z;
    grid.count = msg.count;
    grid.age_s = msg.age_s;  // s since each cell's newest sample: the certainty decays with it
}

namespace {

int8_t class_of(traverse::CellClass c)
{
    switch (c) {
    case traverse::CellClass::traversable: return traversability_map_t::CLASS_TRAVERSABLE;
    case traverse::CellClass::obstacle: return traversability_map_t::CLASS_OBSTACLE;
    case traverse::CellClass::negative_obstacle: return traversability_map_t::CLASS_NEGATIVE_OBSTACLE;
    case traverse::CellClass::unknown: break;
    }
    return traversability_map_t::CLASS_UNKNOWN;
}

}  // namespace

void to_message(const traverse::TraversabilityLayers& layers, const terrain_map_t& map, int64_t seq,
                traversability_map_t& out)
{
    out.utime = map.utime;
    out.seq = seq;
    out.map_seq = map.seq;
    out.pose = map.pose;
    out.resolution = map.resolution;
    out.nx = layers.nx;
    out.ny = layers.ny;
    out.origin_x = map.origin_x;
    out.origin_y = map.origin_y;
    out.residual_yaw = map.residual_yaw;
    out.ncells = static_cast<int32_t>(layers.cells());
    out.cell_class.resize(layers.cells());
    for (std::size_t k = 0; k < layers.cells(); ++k) out.cell_class[k] = class_of(layers.cell_class[k]);
    // Every array exactly ncells long, whatever the layers hold: the encoder reads ncells.
    const auto copy = [n = layers.cells()](const std::vector<float>& from, std::vector<float>& to) {
        to.assign(from.begin(), from.begin() + static_cast<std::ptrdiff_t>(std::min(from.size(), n)));
        to.resize(n, NAN);
    };
    copy(layers.cost, out.cost);
    copy(layers.step_m, out.step_m);
    copy(layers.drop_m, out.drop_m);
    copy(layers.slope_deg, out.slope_deg);
    copy(layers.roughness_m, out.roughness_m);
    copy(layers.span_m, out.span_m);
    copy(layers.certainty, out.certainty);
}

void to_message(const traverse::TraverseResult& result, const traverse::TraverseConfig& config,
                const terrain_map_t& map, int64_t seq, candidate_arcs_t& out)
{
    out.utime = map.utime;
    out.seq = seq;
    out.map_seq = map.seq;
    out.pose = map.pose;
    out.length_m = static_cast<float>(config.arcs.length_m);
    out.swept_width_m = static_cast<float>(config.footprint.width_m + 2.0 * config.arcs.margin_m);
    const std::size_t n = result.arcs.size();
    out.narcs = static_cast<int32_t>(n);
    out.curvature.resize(n);
    out.clear_distance_m.resize(n);
    out.unknown_fraction.resize(n);
    out.mean_cost.resize(n);
    out.merit.resize(n);
    out.blocked.resize(n);
    for (std::size_t k = 0; k < n; ++k) {
        const traverse::ArcVerdict& v = result.arcs[k];
        out.curvature[k] = static_cast<float>(v.curvature_per_m);
        out.clear_distance_m[k] = static_cast<float>(v.clear_distance_m);
        out.unknown_fraction[k] = static_cast<float>(v.unknown_fraction);
        out.mean_cost[k] = static_cast<float>(v.mean_cost);
        out.merit[k] = static_cast<float>(v.merit);
        out.blocked[k] = v.blocked ? 1 : 0;
    }
    out.best = result.best_arc;
}

}  // namespace ugv::traverse_daemon
