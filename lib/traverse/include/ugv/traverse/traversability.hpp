// One update of the traversability analysis: a terrain map in, the traversability layers and
// the arcs' verdicts out, with counters. No I/O; ugv-traverse is its adapter.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "ugv/traverse/candidate_arcs.hpp"
#include "ugv/traverse/cell_classifier.hpp"
#include "ugv/traverse/odometer.hpp"
#include "ugv/traverse/terrain_grid.hpp"

namespace ugv::traverse {

struct TraverseConfig
{
    Footprint footprint;
    ClassifierConfig classifier;
    ArcSetConfig arcs;
};

struct TraverseCounters
{
    uint64_t maps_in = 0;
    uint64_t maps_malformed = 0;      // failed check_grid: dropped, nothing changed
    uint64_t maps_duplicate = 0;      // the same utime as the last map's: dropped
    uint64_t time_restarts = 0;       // utime before the last map's (a log played again): the odometer restarts
    uint64_t obstacle_cells = 0;      // in the last map
    uint64_t negative_obstacle_cells = 0;
    uint64_t unknown_cells = 0;
    uint64_t decayed_cells = 0;       // known in the terrain map but too old: UNKNOWN
    uint64_t arcs_blocked = 0;        // in the last map

    template <class F>
    void visit(F&& f) const
    {
        f("maps_in", maps_in);
        f("maps_malformed", maps_malformed);
        f("maps_duplicate", maps_duplicate);
        f("time_restarts", time_restarts);
        f("obstacle_cells", obstacle_cells);
        f("negative_obstacle_cells", negative_obstacle_cells);
        f("unknown_cells", unknown_cells);
        f("decayed_cells", decayed_cells);
        f("arcs_blocked", arcs_blocked);
    }
};

struct TraverseResult
{
    TraversabilityLayers layers;
    std::vector<ArcVerdict> arcs;
    int best_arc = -1;
};

class Traversability
{
public:
    explicit Traversability(const TraverseConfig& config);  // throws std::invalid_argument
    // Analyses one map. Returns false (counted, result unchanged) for a malformed map or a
    // repeat of the last one; why() then says which check failed.
    bool update(const TerrainGrid& grid);
    const TraverseResult& result() const { return result_; }
    const TraverseCounters& counters() const { return counters_; }
    const std::string& why() const { return why_; }
    const TraverseConfig& config() const { return config_; }

private:
    TraverseConfig config_;
    CellClassifier classifier_;
    std::vector<CandidateArcs> arcs_;  // zero or one: built for the resolution of the maps
    double arcs_resolution_m_ = 0;
    Odometer odometer_;
    int64_t last_utime_us_ = 0;
    TraverseResult result_;
    TraverseCounters counters_;
    std::string why_;
};

}  // namespace ugv::traverse
