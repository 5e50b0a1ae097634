// The terrain map as the traversability analysis reads it: the per-cell layers of a
// terrain_map_t (ugv/terrain_map_t.lcm) with its geometry, as plain values. NaN = unknown.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace ugv::traverse {

struct TerrainGrid
{
    int64_t utime_us = 0;          // the map's pose time
    int64_t seq = 0;
    Eigen::Vector3d position_m{0, 0, 0};  // the pose's ENU position (odometer, decay)
    double resolution_m = 0.2;
    int nx = 0, ny = 0;            // cell (i, j) at i * ny + j, i along +X
    double origin_x_m = 0, origin_y_m = 0;  // corner of cell (0, 0) in the map frame
    double residual_yaw_rad = 0;   // map axes = body axes turned by -residual_yaw
    std::vector<float> mean_z_m, variance_z_m2, max_z_m, min_z_m, age_s;
    std::vector<int32_t> count;

    std::size_t cells() const { return static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny); }
    // Centre of cell (i, j) in the body frame (x forward, y left), m.
    Eigen::Vector2d cell_centre_body(int i, int j) const;
};

// Why a grid cannot be analysed (empty string: it can): sizes that disagree, a resolution
// or origin that is not finite and positive, layers of the wrong length, a known cell with
// a non-finite mean, max or min, max below min, a negative variance or count, more than
// 4 million cells. Checked before anything is computed; a bad grid changes nothing.
std::string check_grid(const TerrainGrid& grid);

}  // namespace ugv::traverse
