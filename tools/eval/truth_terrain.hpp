// The simulator's truth height field judged column by column with the traversability rules
// (docs/traverse.md section 4): every height relative to the column's neighbours, never to
// an absolute ground level. Shared by `ugv-eval traverse` and `ugv-eval compare`.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

#include "ugv/simworld/height_field.hpp"

namespace ugv::eval {

// The defaults are lib/traverse's ClassifierConfig's, so the truth and the map use one rule
// (docs/traverse.md section 4).
struct TruthRules
{
    double max_step_m = 0.2;      // standing this high above the local ground: obstacle
    double max_drop_m = 0.2;      // lying this low below it: negative obstacle
    double step_radius_m = 0.3;   // ugv-eval compare only: its local ground is the lowest column this near
    double ground_radius_m = 1.5; // the local ground: the columns within this, their plane's slope taken
                                  // out, the median
    double max_slope_deg = 25;    // a steeper plane fitted around the column: obstacle ...
    double slope_radius_m = 0.5;  // ... fitted over the columns within this, where no step obstacle is
};

enum class TruthClass : uint8_t { none = 0, traversable = 1, obstacle = 2, negative = 3 };

class TruthTerrain
{
public:
    // Throws std::invalid_argument on a non-positive or non-finite rule.
    TruthTerrain(std::shared_ptr<const simworld::HeightField> field, const TruthRules& rules);

    // The class of column (i, j) (none outside the field or where its height is not finite).
    // Computed on first use and kept: a run's log looks at the same columns many times.
    TruthClass column_class(int i, int j) const;
    // The class of the column under world point (x, y).
    TruthClass class_at(double x_m, double y_m) const;
    // The lowest column within step_radius_m of the column under (x, y): the local ground
    // (NaN outside the field).
    double local_ground_at(double x_m, double y_m) const;
    // The local ground column (i, j) is judged against (the detrended median within
    // ground_radius_m); NaN outside the field or where its height is not finite.
    double ground_height(int i, int j) const;
    // The same over only the columns (a, b) for which include(a, b) is true (NaN if none is).
    double ground_height_over(int i, int j, const std::function<bool(int, int)>& include) const;
    // Column indices of world point (x, y); false outside the field.
    bool column_of(double x_m, double y_m, int& i, int& j) const;

    const simworld::HeightField& field() const { return *field_; }
    const TruthRules& rules() const { return rules_; }

private:
    TruthClass step_class(int i, int j) const;  // by the height over the local ground alone
    TruthClass compute(int i, int j) const;
    double ground_over(int i, int j, const std::function<bool(int, int)>* include) const;

    std::shared_ptr<const simworld::HeightField> field_;
    TruthRules rules_;
    std::vector<std::pair<int, int>> step_disc_;   // offsets within step_radius_m
    std::vector<std::pair<int, int>> slope_disc_;  // offsets within slope_radius_m
    std::vector<std::pair<int, int>> ground_disc_; // every third column within ground_radius_m
    double slope_d2_ = 0;                          // sum of di^2 over it (= of dj^2)
    double max_slope_tan_ = 0;
    mutable std::vector<uint8_t> cache_;           // TruthClass + 1, 0 = not computed
    mutable std::vector<uint8_t> step_cache_;      // the same for step_class
    mutable std::vector<double> ground_cache_;     // ground_height, NaN = not computed (or none)
    mutable std::vector<uint8_t> ground_done_;
    // ground_over's buffers, one pair per depth: a column filter may ask for other grounds.
    struct Scratch
    {
        std::vector<float> around;
        std::vector<std::pair<int, int>> offsets;
    };
    mutable std::deque<Scratch> scratch_;  // growing keeps the outer calls' references valid
    mutable std::size_t depth_ = 0;
};

// The ground as far as the laser has seen it around a column: ground_height over the seen
// columns that are no step obstacles over the ground seen around them (a wall seen from one
// side would tilt the plane of the ground before it). Whether a column is such an obstacle
// is judged on what was seen only: a ramp's top is no step over a drop in its shadow. One per
// map (what is seen differs); it keeps the columns it has judged.
class SeenGround
{
public:
    SeenGround(const TruthTerrain& truth, std::function<bool(int, int)> seen);
    double ground(int i, int j) const;  // NaN outside the field or where no column was seen

private:
    bool step_over_seen(int a, int b) const;

    const TruthTerrain& truth_;
    std::function<bool(int, int)> seen_;
    mutable std::unordered_map<std::int64_t, bool> step_;
};

}  // namespace ugv::eval
