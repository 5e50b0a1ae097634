// The terrain as a grid of flat-topped columns (2.5-D): the simulator's ground truth. Every
// laser beam is ray-cast against it exactly, and ugv-eval compares maps with it, so the map
// is judged against the very surface the laser saw.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace ugv::simworld {

struct HeightField
{
    double origin_x_m = 0.0;  // corner of cell (0, 0), world ENU
    double origin_y_m = 0.0;
    double resolution_m = 0.05;
    int nx = 0;               // cells along x (east)
    int ny = 0;               // cells along y (north)
    std::vector<float> z_m;   // top of column (i, j) at z_m[i * ny + j], m up

    HeightField() = default;
    HeightField(double origin_x, double origin_y, double resolution, int cells_x, int cells_y, float z);

    float& at(int i, int j) { return z_m[static_cast<std::size_t>(i) * static_cast<std::size_t>(ny) + static_cast<std::size_t>(j)]; }
    float at(int i, int j) const { return z_m[static_cast<std::size_t>(i) * static_cast<std::size_t>(ny) + static_cast<std::size_t>(j)]; }
    // Centre of cell (i, j).
    double cell_x(int i) const { return origin_x_m + (i + 0.5) * resolution_m; }
    double cell_y(int j) const { return origin_y_m + (j + 0.5) * resolution_m; }
    // Height of the column under (x, y); NaN outside the field.
    double height_at(double x_m, double y_m) const;
};

// Distance (m) along the ray from origin in direction unit_dir to the first surface of the
// field (a column top or side), or +infinity when nothing is hit within max_range_m or the
// ray leaves the field. The origin must lie above the surface.
double ray_cast(const HeightField& field, const Eigen::Vector3d& origin, const Eigen::Vector3d& unit_dir,
                double max_range_m);

// The truth file ugv-sim writes and ugv-eval reads: a text line
// "UGVHF1 <nx> <ny> <resolution_m> <origin_x_m> <origin_y_m>\n" then nx*ny float32
// little-endian heights in the order of z_m.
std::string encode_height_field(const HeightField& field);
// Throws std::invalid_argument naming what is wrong.
HeightField decode_height_field(const std::string& bytes);

}  // namespace ugv::simworld
