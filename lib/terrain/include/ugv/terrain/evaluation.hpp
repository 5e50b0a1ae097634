// A map against ground truth: the height error of the known cells (RMSE, bias), coverage,
// and obstacle detection (cells whose true height stands above the local ground by a threshold).
#pragma once

#include <cstdint>
#include <functional>

#include "ugv/terrain/terrain_mapper.hpp"

namespace ugv::terrain {

struct MapMetrics
{
    int cells = 0;            // cells compared (inside the truth's domain)
    int known = 0;            // of which known (mean not NaN)
    double coverage = 0.0;    // known / cells
    double bias_m = 0.0;      // mean of (map - truth) over known cells
    double rmse_m = 0.0;      // root mean square of (map - truth) over known cells
    double mean_cell_variance_m2 = 0.0;  // mean of the cells' own variance (eq. 22 or 32)
    int obstacle_cells = 0;   // known cells whose truth stands the threshold or more above the local ground
    int obstacles_detected = 0;  // ... and whose map height stands above it by more than half the threshold
    int false_obstacles = 0;  // known cells below the threshold that the map puts above half of it
    // The highest sample of each known cell (max_z_m) against the truth: a wall's cell
    // says how tall the wall is where its mean, which also holds the ground in front of
    // it and the face below the top, does not. 0 when the map has no max_z_m.
    double max_bias_m = 0.0;   // mean of (max - truth) over known cells
    double max_rmse_m = 0.0;
    double obstacle_mean_error_m = 0.0;  // mean of (mean - truth) over known obstacle cells
    double obstacle_max_error_m = 0.0;   // mean of (max - truth) over known obstacle cells
};

// truth(x_m, y_m): the ENU height at a world position, NaN where it is not defined (those
// cells are not compared). Cells are placed in the world with the snapshot's pose.
// ground(x_m, y_m): the local ground there (e.g. the lowest true height within 0.3 m), which
// obstacle heights are measured from (NaN: the cell is no obstacle); without it, 0.
MapMetrics evaluate(const MapSnapshot& map, const std::function<double(double, double)>& truth,
                    double obstacle_height_m = 0.2, const std::function<double(double, double)>& ground = {});

// ENU position of the centre of cell (i, j) of the snapshot.
Eigen::Vector2d cell_centre_world(const MapSnapshot& map, int i, int j);

// An area in the vehicle's body frame laid on the ground: x in [x0_m, x1_m] ahead of the
// reference point, |y| <= half_width_m.
struct BodyArea
{
    double x0_m = 2.0, x1_m = 20.0, half_width_m = 6.0;
};

struct AreaCoverage
{
    int cells = 0;          // cells of the map whose centre lies in the area
    int known = 0;          // of which known (mean not NaN)
    double coverage = 0.0;  // known / cells
};

// How much of an area around the vehicle the map knows: no truth needed, the same for any
// sensor set (docs/simulator.md, "Two lasers"). Cells are placed with the map's own yaw
// residual, so the area stays on the vehicle between the map's rotations.
AreaCoverage area_coverage(const MapSnapshot& map, const BodyArea& area);

}  // namespace ugv::terrain
