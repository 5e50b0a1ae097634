// Terrain grids for the traversability tests: every cell filled from a list of sample
// heights (count, mean, variance, max, min as the terrain map keeps them, classical).
#pragma once

#include <cmath>
#include <functional>
#include <vector>

#include "ugv/traverse/terrain_grid.hpp"

namespace ugv::traverse::test {

inline TerrainGrid empty_grid(int nx = 150, int ny = 150, double res = 0.2)
{
    TerrainGrid g;
    g.utime_us = 1'000'000;
    g.nx = nx;
    g.ny = ny;
    g.resolution_m = res;
    g.origin_x_m = -0.5;  // the rear bumper, as ugv-terrain's default
    g.origin_y_m = -0.5 * ny * res;
    const std::size_t n = g.cells();
    g.mean_z_m.assign(n, NAN);
    g.variance_z_m2.assign(n, NAN);
    g.max_z_m.assign(n, NAN);
    g.min_z_m.assign(n, NAN);
    g.count.assign(n, 0);
    g.age_s.assign(n, NAN);
    return g;
}

inline void set_samples(TerrainGrid& g, int i, int j, const std::vector<double>& z, double age_s = 0.1)
{
    const std::size_t k = static_cast<std::size_t>(i) * g.ny + j;
    double sum = 0, sum2 = 0, hi = -INFINITY, lo = INFINITY;
    for (double v : z) {
        sum += v;
        sum2 += v * v;
        hi = std::max(hi, v);
        lo = std::min(lo, v);
    }
    const double n = static_cast<double>(z.size());
    const double mean = sum / n;
    g.count[k] = static_cast<int32_t>(z.size());
    g.mean_z_m[k] = static_cast<float>(mean);
    g.variance_z_m2[k] = static_cast<float>(std::max(0.0, sum2 / n - mean * mean));
    g.max_z_m[k] = static_cast<float>(hi);
    g.min_z_m[k] = static_cast<float>(lo);
    g.age_s[k] = static_cast<float>(age_s);
}

// Cell centre in the body frame (residual yaw 0).
inline double cx(const TerrainGrid& g, int i) { return g.origin_x_m + (i + 0.5) * g.resolution_m; }
inline double cy(const TerrainGrid& g, int j) { return g.origin_y_m + (j + 0.5) * g.resolution_m; }

// Every cell from a height function sampled at 4 points inside it (what a cell of a
// sloping or stepped surface holds), with a little seeded noise.
inline void fill(TerrainGrid& g, const std::function<double(double x, double y)>& h, int per_quarter = 3)
{
    unsigned seed = 12345;
    auto noise = [&] {
        seed = seed * 1103515245u + 12345u;
        return ((seed >> 16) % 1000 / 1000.0 - 0.5) * 0.02;  // +-1 cm
    };
    for (int i = 0; i < g.nx; ++i)
        for (int j = 0; j < g.ny; ++j) {
            std::vector<double> z;
            for (double dx : {-0.25, 0.25})
                for (double dy : {-0.25, 0.25})
                    for (int r = 0; r < per_quarter; ++r)
                        z.push_back(h(cx(g, i) + dx * g.resolution_m, cy(g, j) + dy * g.resolution_m) + noise());
            set_samples(g, i, j, z);
        }
}

}  // namespace ugv::traverse::test
