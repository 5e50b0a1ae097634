// Maps shared by the traversability tests and benchmarks: a map like the demo's and
// random ones.
#pragma once

#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include "ugv_test/terrain_grid_builder.hpp"
#include "ugv/traverse/cell_classifier.hpp"

namespace ugv::traverse::test {

// allow_avx2 for a test's scope, then back to the default: the comparisons run with the AVX2
// loops and with the baseline ones (GENERATE(true, false)), so that neither goes untested
// on a machine with AVX2.
struct Avx2Allowed
{
    explicit Avx2Allowed(bool allowed) { allow_avx2(allowed); }
    ~Avx2Allowed() { allow_avx2(true); }
    Avx2Allowed(const Avx2Allowed&) = delete;
    Avx2Allowed& operator=(const Avx2Allowed&) = delete;
};

// A cell's extreme (max or min) when min_support samples stand near it, else its mean
// (docs/traverse.md section 1, step 2), written plainly.
inline float supported(float mean, float extreme, float var, int32_t count, double min_support)
{
    const double d = static_cast<double>(extreme) - mean;
    if (std::abs(d) < 1e-4) return extreme;
    return count * static_cast<double>(var) / (d * d) >= min_support ? extreme : mean;
}

// The heights the local ground is taken over (section 1, step 4), in a grid's mean_z_m for
// local_ground_reference: a known cell's mean, but its supported bottom when the mean stands
// above all its own samples (published max = mean > min), its supported top when below them;
// any other cell's mean.
inline TerrainGrid ground_levels(const TerrainGrid& g, const std::vector<uint8_t>& known, double min_support)
{
    TerrainGrid levels;
    levels.resolution_m = g.resolution_m;
    levels.nx = g.nx;
    levels.ny = g.ny;
    levels.mean_z_m = g.mean_z_m;
    for (std::size_t k = 0; k < g.cells(); ++k) {
        if (!known[k]) continue;
        const float var = std::isfinite(g.variance_z_m2[k]) ? g.variance_z_m2[k] : 0.0f, mean = g.mean_z_m[k];
        if (g.max_z_m[k] == mean && g.min_z_m[k] < mean)
            levels.mean_z_m[k] = supported(mean, g.min_z_m[k], var, g.count[k], min_support);
        else if (g.min_z_m[k] == mean && g.max_z_m[k] > mean)
            levels.mean_z_m[k] = supported(mean, g.max_z_m[k], var, g.count[k], min_support);
    }
    return levels;
}

// The cells the local ground is fitted to (section 1, step 4), written plainly: the known
// ones whose supported top and bottom lie less than max_step apart (a cell that holds a step
// is no ground level).
inline std::vector<uint8_t> ground_points(const TerrainGrid& g, const std::vector<uint8_t>& known, double min_support,
                                          double max_step)
{
    std::vector<uint8_t> points(g.cells(), 0);
    for (std::size_t k = 0; k < g.cells(); ++k) {
        if (!known[k]) continue;
        const float var = std::isfinite(g.variance_z_m2[k]) ? g.variance_z_m2[k] : 0.0f;
        const float top = supported(g.mean_z_m[k], g.max_z_m[k], var, g.count[k], min_support);
        const float bottom = supported(g.mean_z_m[k], g.min_z_m[k], var, g.count[k], min_support);
        points[k] = static_cast<double>(top - bottom) >= max_step ? 0 : 1;
    }
    return points;
}

// Like the demo's (150x150 at 0.2 m): rough ground, boxes, a wall, a ditch, the dead zone
// and the shadows unknown.
inline TerrainGrid demo_like_map()
{
    TerrainGrid g = empty_grid();
    fill(g, [](double x, double y) {
        double z = 750.0 + 0.05 * std::sin(0.7 * x) * std::cos(0.5 * y) + 0.02 * x;
        if (x > 8 && x < 8.6 && y > -3 && y < -2.4) z += 0.6;        // box
        if (y > 7 && y < 7.3 && x > 4 && x < 25) z += 3.0;           // wall
        if (x > 14 && x < 15 && y > -6 && y < 2) z -= 0.4;           // ditch
        if (x > 18 && x < 20 && y > 2 && y < 4) z += 0.3;            // low box
        return z;
    });
    // Unknown: the dead zone before 3 m, behind the wall, beyond 25 m, and a third of the rest.
    for (int i = 0; i < g.nx; ++i)
        for (int j = 0; j < g.ny; ++j) {
            const double x = cx(g, i), y = cy(g, j);
            if (x < 3 || y > 7.3 || x > 25 || ((i * 7 + j * 13) % 3 == 0 && x > 15)) {
                const std::size_t k = static_cast<std::size_t>(i) * g.ny + j;
                g.count[k] = 0;
                g.mean_z_m[k] = g.max_z_m[k] = g.min_z_m[k] = g.variance_z_m2[k] = NAN;
            }
        }
    g.position_m = {0, 0, 750.0};
    return g;
}

// Rough ground at `base` with a tilt, boxes, walls and ditches at random, a share of the
// cells unknown (in blobs and scattered), some single stray samples.
inline TerrainGrid random_map(std::mt19937& rng, int nx, int ny, double base)
{
    std::uniform_real_distribution<double> u(0.0, 1.0);
    TerrainGrid g = empty_grid(nx, ny);
    const double tx = (u(rng) - 0.5) * 0.6, ty = (u(rng) - 0.5) * 0.6, rough = 0.05 * u(rng);
    struct Box { double x0, x1, y0, y1, dz; };
    std::vector<Box> boxes;
    const double x_end = g.origin_x_m + nx * g.resolution_m, y0 = g.origin_y_m, y_end = y0 + ny * g.resolution_m;
    for (int b = 0; b < 12; ++b) {
        const double x = g.origin_x_m + u(rng) * (x_end - g.origin_x_m), y = y0 + u(rng) * (y_end - y0);
        const double w = 0.1 + u(rng) * 1.5, l = 0.1 + u(rng) * (b % 4 == 0 ? 8.0 : 1.5);
        const double dz = b % 3 == 0 ? -(0.15 + u(rng) * 0.5) : 0.1 + u(rng) * (b % 5 == 0 ? 3.0 : 1.0);
        boxes.push_back(b % 2 ? Box{x, x + l, y, y + w, dz} : Box{x, x + w, y, y + l, dz});
    }
    fill(g, [&](double x, double y) {
        double z = base + tx * x + ty * y + rough * std::sin(1.3 * x) * std::cos(0.9 * y);
        for (const Box& b : boxes)
            if (x >= b.x0 && x < b.x1 && y >= b.y0 && y < b.y1) z += b.dz;
        return z;
    });
    const int blobs = 1 + static_cast<int>(u(rng) * 6);
    for (int b = 0; b < blobs; ++b) {
        const int ci = static_cast<int>(u(rng) * nx), cj = static_cast<int>(u(rng) * ny), r = 1 + static_cast<int>(u(rng) * 12);
        for (int i = std::max(0, ci - r); i < std::min(nx, ci + r); ++i)
            for (int j = std::max(0, cj - r); j < std::min(ny, cj + r); ++j) {
                const std::size_t k = static_cast<std::size_t>(i) * ny + j;
                g.count[k] = 0;
                g.mean_z_m[k] = g.max_z_m[k] = g.min_z_m[k] = g.variance_z_m2[k] = NAN;
            }
    }
    const double scattered = u(rng) * 0.5;
    for (std::size_t k = 0; k < g.cells(); ++k)
        if (u(rng) < scattered) {
            g.count[k] = 0;
            g.mean_z_m[k] = g.max_z_m[k] = g.min_z_m[k] = g.variance_z_m2[k] = NAN;
        }
    for (int s = 0; s < 20; ++s) {
        const int i = static_cast<int>(u(rng) * nx), j = static_cast<int>(u(rng) * ny);
        set_samples(g, i, j, {base + 2.0 * (u(rng) - 0.3)});
    }
    return g;
}

}  // namespace ugv::traverse::test
