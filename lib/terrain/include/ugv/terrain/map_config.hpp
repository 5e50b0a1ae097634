// Configuration of the terrain map (docs/ARCHITECTURE.md, "The terrain map"; report
// sections 3 and 6).
#pragma once

#include <cmath>
#include <cstdint>

#include "ugv/terrain/cell_sums.hpp"

namespace ugv::terrain {

enum class MapMode : int8_t {
    egocentric = 0,     // the report's map: wraps on forward motion, rotates in theta_d steps
    world_aligned = 1,  // a 2-D ring buffer on ENU axes that only translates; rotated on output
};

// How section 3.5 spreads a point (docs/terrain.md, "Section 3.5: spreading").
enum class SpreadForm : int8_t {
    exact = 0,        // cell by cell: the reference
    summed_area = 1,  // the same sums up to rounding, at a cost that does not grow with the footprint
    centred = 2,      // summed-area with each share at its cell's centre: weight, mean, variance,
                      // count and extremes as exact up to rounding; the edge cells' x/y sums not
};

struct MapConfig
{
    double grid_size_m = 0.2;   // G_l
    double extent_x_m = 30.0;   // X_max, forward of the reference point
    double extent_y_m = 30.0;   // Y_max, centred on the reference point (-Y_max/2 .. +Y_max/2)
    double theta_d_rad = 5.0 * M_PI / 180.0;  // rotate once the summed yaw passes this
    StatisticsKind statistics = StatisticsKind::variance_weighted;
    MapMode mode = MapMode::egocentric;
    // The map's reference point in the body frame (m). Row 0 of the map starts here. The
    // default is the rear bumper (report section 8): an obstacle beside the vehicle stays
    // in the map until the whole vehicle has passed it.
    double reference_x_m = -0.5;
    double reference_y_m = 0.0;
    bool spread = true;          // section 3.5: spread a point whose sigma exceeds G_l
    int spread_max_cells = 2;    // footprint half-width cap, cells (1..4)
    SpreadForm spread_form = SpreadForm::summed_area;  // src/spread_sums.hpp
    double min_variance_m2 = 1e-6;  // floor of a point's variance (a zero variance would be an infinite weight)
    int64_t pose_history_us = 2'000'000;
    double max_interpolation_span_s = 0.1;  // longer point batches are fused in runs that span at most this
    // false: a longer batch goes point by point, each point's pose interpolated on its own
    // (the scalar reference the runs are tested against).
    bool split_long_batches = true;

    int nx() const { return static_cast<int>(std::lround(extent_x_m / grid_size_m)); }
    int ny() const { return static_cast<int>(std::lround(extent_y_m / grid_size_m)); }
    // Throws std::invalid_argument naming the field when a value is out of range.
    void validate() const;
};

inline constexpr int kMaxSpreadCells = 4;

}  // namespace ugv::terrain
