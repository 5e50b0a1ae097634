// Per cell of a terrain map: is it traversable, an obstacle, a negative obstacle (ditch,
// drop-off) or unknown, with a cost and the quantities behind the verdict. The same grid
// and odometer give the same layers (the class keeps only working memory).
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "ugv/traverse/odometer.hpp"
#include "ugv/traverse/terrain_grid.hpp"

namespace ugv::traverse {

enum class CellClass : int8_t { unknown = 0, traversable = 1, obstacle = 2, negative_obstacle = 3 };

struct ClassifierConfig
{
    double max_step_m = 0.2;          // a top this high above the local ground is an obstacle
    double max_drop_m = 0.2;          // a bottom this deep below it is a negative obstacle
    double step_radius_m = 0.3;       // step and drop against the cells within this
    double face_mean_step_m = 0.07;   // a step of max_step is a vertical face (obstacle) when the
                                      // cell's mean also stands this far above the lowest mean there
    double max_slope_deg = 25;        // a steeper neighbourhood is an obstacle
    double slope_radius_m = 0.5;      // the plane for the slope is fitted over this radius
    double ground_radius_m = 1.5;     // the local ground is taken over this radius
    double shadow_radius_m = 0.6;     // a drop's floor is looked for this far across unknown cells
    double max_roughness_m = 0.15;    // a cell's height spread (sd) that costs 1
    double min_support_samples = 2;   // samples near a cell's max (min) for it to be its top (bottom)
    double max_age_s = 60;            // data this old is UNKNOWN (certainty 0)
    double max_driven_m = 40;         // data seen this many metres of driving ago is UNKNOWN
};

struct TraversabilityLayers
{
    int nx = 0, ny = 0;
    std::vector<CellClass> cell_class;
    std::vector<float> cost;         // [0, 1], 1 for obstacles; NaN unknown
    std::vector<float> step_m;       // step up from the neighbours to this cell's supported top
    std::vector<float> drop_m;       // drop from the neighbours down to its supported bottom
    std::vector<float> slope_deg;
    std::vector<float> roughness_m;  // sqrt(variance)
    std::vector<float> span_m;       // max - min
    std::vector<float> ground_m;     // the local ground's height under the cell (ENU)
    std::vector<float> certainty;    // [0, 1]

    void reset(int nx, int ny);
    std::size_t cells() const { return cell_class.size(); }
};

class DropsAcrossUnknown;

class CellClassifier
{
public:
    explicit CellClassifier(const ClassifierConfig& config);  // throws std::invalid_argument on a bad config
    // The grid must pass check_grid; out is resized to it. odometer says how far the vehicle
    // has driven since each cell's newest sample (the decay of certainty).
    void classify(const TerrainGrid& grid, const Odometer& odometer, TraversabilityLayers& out);
    const ClassifierConfig& config() const { return config_; }

private:
    // ground := the local ground under every known cell (known_), fitted to the levels of
    // the cells of ground_points_ (step 3 of classify).
    void local_ground(const TerrainGrid& grid, double radius_m, double max_step_m, std::vector<float>& ground);

    ClassifierConfig config_;
    // Per-cell working layers, kept between calls so an update allocates nothing.
    std::vector<float> top_, bottom_, lowest_, highest_, lowest_level_, lowest_top_, lattice_;
    std::vector<std::array<float, 2>> lattice_slope_;
    std::vector<uint8_t> measured_, edge_, known_, ground_points_, row_known_, face_;
    std::vector<float> row_sums_, line_w_, line_z_, line_o_, moments_, tangent_, slope_fd_;
    std::vector<const float*> slope_rows_;
    std::vector<float> window_;
    std::vector<std::size_t> rims_;  // faces with a drop beside them (step 3)
    // The offsets of the drops across unknown cells (step 3), built for the grid's
    // resolution when it changes.
    std::shared_ptr<const DropsAcrossUnknown> drops_;
    TerrainGrid levels_;  // the heights the local ground is taken over (cell_level), in mean_z_m
    // The local ground's: known flags (float), a lattice row's column sums, the means split
    // by column parity, a window's points (rows padded to vectors of 8, NaN where unknown)
    // and the same levelled, its columns' offsets and which lanes hold a column, the values
    // gathered for the percentile's last step; per lattice square, whether it holds a known
    // cell; per lattice point, whether a known cell reads it; per 8 points of a window, the
    // ones to test again in double; per lane of a window's rows: the heights' sums.
    std::vector<float> known_f_, column_sums_;
    std::vector<float> parity_means_, win_v_, win_lev_, win_q_, win_sel_;
    std::vector<uint8_t> square_known_, needed_, win_flags_;
    std::vector<int32_t> lane_known_;
    std::vector<double> lane_z_, lane_pz_;
};

}  // namespace ugv::traverse

namespace ugv::traverse {

// Whether the classifier may use its AVX2 loops on a CPU that has AVX2 (the default); off,
// it uses the 4-lane ones of the x86-64 baseline. The outputs are the same either way; the
// tests turn it off to check the fallback on a machine with AVX2. Process-wide.
void allow_avx2(bool allowed);

// The slope the classifier reports, written plainly: the least-squares plane through the
// means of the cells (p, q) with counts[p * ny + q] true in the square window of half-width
// half_width around (i, j), and its steepest angle in degrees; NaN with fewer than half the
// window's cells or cells on a line. The classifier's separable sums are tested against it.
double slope_reference_deg(const TerrainGrid& grid, const std::vector<uint8_t>& counts, int i, int j, int half_width);

// The local ground the classifier uses (docs/traverse.md, section 1, step 4), written plainly:
// ground := under each cell with known[k] true, the level interpolated from the lattice
// points' planes and 40th percentiles of grid.mean_z_m over the cells with points[k] true
// within radius_m (the classifier passes its cells' levels there, and as points its known
// cells that hold no step). The classifier's is tested against it.
void local_ground_reference(const TerrainGrid& grid, const std::vector<uint8_t>& known,
                            const std::vector<uint8_t>& points, double radius_m, double max_step_m,
                            std::vector<float>& ground);

}  // namespace ugv::traverse
