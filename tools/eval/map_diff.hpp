// ugv-eval diff A.lcm B.lcm: the terrain maps of two logs, cell by cell at the same place in
// the world (each cell of B looked up in A through both maps' poses), so two runs of the same
// drive can be compared even when their maps refer to slightly different poses.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace ugv::eval {

class MapDiffCommand
{
public:
    // Adds the `diff` subcommand and its options to app.
    explicit MapDiffCommand(CLI::App& app);
    MapDiffCommand(const MapDiffCommand&) = delete;  // CLI11 holds references to the members
    MapDiffCommand& operator=(const MapDiffCommand&) = delete;
    bool chosen() const { return sub_->parsed(); }
    // Prints one JSON summary line (and one per pair with --all). Exit status: 0 when at
    // least one pair was compared and every pair is within the tolerances, 1 otherwise, 2
    // when a log cannot be read.
    int run() const;

private:
    CLI::App* sub_;
    std::string log_a_, log_b_, channel_ = "TERRAIN_MAP", pair_ = "time";
    // Tolerances; a negative one is no limit.
    double max_dz_m_ = -1.0;       // largest |z_A - z_B| in a cell known in both
    double max_rms_dz_m_ = -1.0;   // largest RMS of z_A - z_B over the cells known in both
    double max_one_sided_ = -1.0;  // largest fraction of cells known in one map only, per pair
    bool all_ = false;
};

}  // namespace ugv::eval
