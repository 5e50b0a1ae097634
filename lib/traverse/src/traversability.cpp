#include "ugv/traverse/traversability.hpp"

#include <stdexcept>

namespace ugv::traverse {

Traversability::Traversability(const TraverseConfig& config) : config_(config), classifier_(config.classifier)
{
    // Checks the arc set and footprint now (at a nominal resolution): a bad config fails at
    // start-up, not at the first map.
    CandidateArcs check(config.arcs, config.footprint, 0.2);
    (void)check;
}

bool Traversability::update(const TerrainGrid& grid)
{
    ++counters_.maps_in;
    why_ = check_grid(grid);
    if (!why_.empty()) {
        ++counters_.maps_malformed;
        return false;
    }
    if (grid.utime_us == last_utime_us_) {
        why_ = "the same utime as the last map's";
        ++counters_.maps_duplicate;
        return false;
    }
    if (grid.utime_us < last_utime_us_) ++counters_.time_restarts;  // Odometer::add restarts too
    last_utime_us_ = grid.utime_us;
    if (arcs_.empty() || arcs_resolution_m_ != grid.resolution_m) {
        arcs_.clear();
        arcs_.emplace_back(config_.arcs, config_.footprint, grid.resolution_m);
        arcs_resolution_m_ = grid.resolution_m;
    }
    odometer_.add(grid.utime_us, grid.position_m);
    classifier_.classify(grid, odometer_, result_.layers);
    arcs_.front().judge(grid, result_.layers, result_.arcs, result_.best_arc);

    // Counted without a branch (so that the loop vectorises).
    const CellClass* cls = result_.layers.cell_class.data();
    const float* certainty = result_.layers.certainty.data();
    const int32_t* count = grid.count.data();
    uint32_t obstacle = 0, negative = 0, unknown = 0, decayed = 0;
    for (std::size_t k = 0; k < grid.cells(); ++k) {
        obstacle += cls[k] == CellClass::obstacle ? 1u : 0u;
        negative += cls[k] == CellClass::negative_obstacle ? 1u : 0u;
        unknown += cls[k] == CellClass::unknown ? 1u : 0u;
        decayed += cls[k] == CellClass::unknown && count[k] > 0 && certainty[k] <= 0.0f ? 1u : 0u;
    }
    counters_.obstacle_cells = obstacle;
    counters_.negative_obstacle_cells = negative;
    counters_.unknown_cells = unknown;
    counters_.decayed_cells = decayed;
    counters_.arcs_blocked = 0;
    for (const ArcVerdict& v : result_.arcs) counters_.arcs_blocked += v.blocked ? 1 : 0;
    return true;
}

}  // namespace ugv::traverse
