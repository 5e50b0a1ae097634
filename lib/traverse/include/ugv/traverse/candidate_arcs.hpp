// The candidate arcs of the report's figure 20: arcs of constant curvature from the body
// origin, each swept by the vehicle's footprint widened by a margin, judged on a
// traversability map: how far the vehicle can drive along it before touching an obstacle,
// how much of what it sweeps is unknown, a merit, blocked or not.
#pragma once

#include <cstdint>
#include <vector>

#include "ugv/traverse/cell_classifier.hpp"
#include "ugv/traverse/terrain_grid.hpp"

namespace ugv::traverse {

struct Footprint  // body frame: origin at the rear axle centre on the ground
{
    double rear_x_m = -0.5;   // rear bumper
    double front_x_m = 2.0;   // front bumper
    double width_m = 1.6;
};

enum class UnknownPolicy {
    optimistic,  // unknown cells do not block; they lower the merit
    cautious,    // an arc sweeping more than max_unknown_fraction unknown is blocked
};

struct ArcSetConfig
{
    int count = 25;                        // arcs, curvatures evenly spaced
    double max_curvature_per_m = 0.2;      // the turning limit: 1 / minimum radius; arcs span ±
    double length_m = 12.0;                // judged along the body origin's path
    double margin_m = 0.3;                 // added on each side of the footprint
    UnknownPolicy unknown_policy = UnknownPolicy::optimistic;
    double max_unknown_fraction = 0.5;     // cautious policy only
    double unknown_weight = 0.5;           // in the merit: 1 - unknown_fraction * this
};

struct ArcVerdict
{
    double curvature_per_m = 0;
    double clear_distance_m = 0;  // length_m when nothing is hit
    double unknown_fraction = 0;  // over the cells swept before clear_distance_m
    double mean_cost = 0;         // over the known ones among them
    double merit = 0;             // (clear / length) (1 - unknown_fraction unknown_weight) (1 - mean_cost)
    bool blocked = false;
};

// The sweeps are computed once (body frame, at the grid's resolution); judging them on a
// map then costs one lookup per swept cell.
class CandidateArcs
{
public:
    // Throws std::invalid_argument on a bad config (count < 1, curvature that makes the
    // footprint turn inside itself, non-positive length or resolution...).
    CandidateArcs(const ArcSetConfig& config, const Footprint& footprint, double resolution_m);
    // One verdict per arc, in order of curvature (right to left); best = the arc not blocked
    // with the highest merit, -1 when all are blocked. The layers must belong to grid.
    void judge(const TerrainGrid& grid, const TraversabilityLayers& layers, std::vector<ArcVerdict>& out,
               int& best) const;

    // A swept cell of the body-frame sweep: its centre (body frame) and the arc length at
    // which the footprint first covers it.
    struct SweptCell { float x_m, y_m, s_m; };
    const std::vector<SweptCell>& sweep(int arc) const { return sweeps_[static_cast<std::size_t>(arc)]; }
    double curvature(int arc) const { return curvatures_[static_cast<std::size_t>(arc)]; }
    int count() const { return static_cast<int>(curvatures_.size()); }
    const ArcSetConfig& config() const { return config_; }
    const Footprint& footprint() const { return footprint_; }

private:
    ArcSetConfig config_;
    Footprint footprint_;
    double resolution_m_;
    std::vector<double> curvatures_;
    std::vector<std::vector<SweptCell>> sweeps_;  // cells of half the resolution, sorted by s
    std::vector<std::vector<float>> sweep_x_, sweep_y_;  // their centres' x and y apart (judge's loop)
    // Per map cell: the last arc that counted it. 16 bits (cleared when the stamp wraps, every
    // 65535 arcs): its addresses then do not keep step with the 4-byte layers' the judge reads
    // in the same loop (with 32 bits, a store to seen_ at the same offset modulo 4 KiB as the
    // next load from the cost layer made the judge 1.5 times slower, for the same instructions).
    mutable std::vector<uint16_t> seen_;
    mutable uint16_t stamp_ = 0;
};

// Where the footprint of a vehicle driving s_m along an arc of curvature k covers point p
// (body frame at the start): the smallest s in [0, max_s_m] at which p lies inside the
// footprint widened by margin_m, or NaN if it never does. The plain definition the sweeps
// are tested against, and what ugv-eval uses to judge arcs on the truth.
double first_cover_s(double curvature_per_m, const Footprint& footprint, double margin_m, double max_s_m,
                     const Eigen::Vector2d& p_body_m, double step_m);

}  // namespace ugv::traverse
