// ugv-eval traverse LOG --truth RUN/truth.hf: the traversability maps of a log (and the
// candidate arcs judged on each) against the simulator's truth height field. Definitions in
// docs/traverse.md section 4.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

#include "truth_terrain.hpp"

namespace ugv::eval {

// The counts of one map (or, added up, of a log).
struct TraverseScore
{
    // Cells whose centre lies 0..range_m ahead of the vehicle (body x), by their truth.
    long obstacle_cells = 0, obstacle_seen = 0, obstacle_detected = 0;
    long negative_cells = 0, negative_seen = 0, negative_detected = 0;
    long traversable_known = 0, false_obstacles = 0, false_negative_obstacles = 0;
    // Of the known obstacle cells (both kinds), those where the terrain map the map was
    // computed from holds a sample of the obstacle itself, not only of the ground at its foot,
    // and how many of those were detected.
    long sampled = 0, sampled_detected = 0;
    // Arcs judged on the map, against the truth restricted to what the laser has seen and
    // against every truth column.
    long arcs = 0, arcs_blocked = 0;
    long arcs_truth_blocked = 0, arcs_agree = 0;
    long arcs_truth_blocked_unrestricted = 0, arcs_agree_unrestricted = 0;
    // The same against the truth's obstacles whose cells the laser sampled (as `sampled`), over
    // the arcs whose map came with its terrain map.
    long arcs_with_terrain = 0, arcs_truth_blocked_sampled = 0, arcs_agree_sampled = 0;

    void add(const TraverseScore& o);
    // JSON members (no braces): the counts and the ratios (null where nothing was counted).
    std::string json() const;
};

class TraverseScoreCommand
{
public:
    explicit TraverseScoreCommand(CLI::App& app);  // adds the `traverse` subcommand
    TraverseScoreCommand(const TraverseScoreCommand&) = delete;  // CLI11 holds references to the members
    TraverseScoreCommand& operator=(const TraverseScoreCommand&) = delete;
    bool chosen() const { return sub_->parsed(); }
    // One JSON line per map scored and a summary line. Exit status 0 when at least one map
    // was scored, 1 when none, 2 when the log or the truth cannot be read.
    int run() const;

private:
    CLI::App* sub_;
    std::string log_, truth_, channel_ = "TRAVERSABILITY_MAP", arcs_channel_ = "ARCS",
                terrain_channel_ = "TERRAIN_MAP", misses_;
    double range_m_ = 15.0;
    double rear_x_m_, front_x_m_;  // the footprint's, lengthwise; its width is the arcs' swept width
    TruthRules rules_;
    bool all_ = false, last_ = false;
    std::string pose_ = "auto";  // auto | truth | estimate: where the maps are placed in the world
};

}  // namespace ugv::eval
