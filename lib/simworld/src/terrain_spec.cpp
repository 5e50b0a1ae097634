#include "ugv/simworld/terrain_spec.hpp"

#include <algorithm>
#include <cmath>

namespace ugv::simworld {

namespace {

// A reproducible value in [-1, 1] for a lattice node.
double lattice_value(int64_t ix, int64_t iy, uint32_t seed)
{
    uint64_t h = static_cast<uint64_t>(ix) * 0x9E3779B97F4A7C15ull ^ static_cast<uint64_t>(iy) * 0xC2B2AE3D27D4EB4Full ^
                 (static_cast<uint64_t>(seed) << 32);
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdull;
    h ^= h >> 33;
    h *= 0xc4ceb9fe1a85ec53ull;
    h ^= h >> 33;
    return static_cast<double>(h >> 11) / static_cast<double>(1ull << 52) - 1.0;
}

double smoothstep(double t) { return t * t * (3.0 - 2.0 * t); }

double distance_to_segment(double px, double py, const WallSpec& w)
{
    const double vx = w.x1_m - w.x0_m, vy = w.y1_m - w.y0_m;
    const double len2 = vx * vx + vy * vy;
    const double t = len2 > 0 ? std::clamp(((px - w.x0_m) * vx + (py - w.y0_m) * vy) / len2, 0.0, 1.0) : 0.0;
    return std::hypot(px - (w.x0_m + t * vx), py - (w.y0_m + t * vy));
}

double ramp_fraction(const RampSpec& r, double x, double y)
{
    switch (r.rises_towards) {
    case Direction::east: return (x - r.area.x0_m) / (r.area.x1_m - r.area.x0_m);
    case Direction::west: return (r.area.x1_m - x) / (r.area.x1_m - r.area.x0_m);
    case Direction::north: return (y - r.area.y0_m) / (r.area.y1_m - r.area.y0_m);
    case Direction::south: return (r.area.y1_m - y) / (r.area.y1_m - r.area.y0_m);
    }
    return 0.0;
}

}  // namespace

double roughness_at(const TerrainSpec& s, double x_m, double y_m)
{
    if (s.roughness_m <= 0.0) return 0.0;
    const double gx = x_m / s.roughness_wavelength_m, gy = y_m / s.roughness_wavelength_m;
    const double fx = std::floor(gx), fy = std::floor(gy);
    const auto ix = static_cast<int64_t>(fx), iy = static_cast<int64_t>(fy);
    const double tx = smoothstep(gx - fx), ty = smoothstep(gy - fy);
    const double a = lattice_value(ix, iy, s.seed), b = lattice_value(ix + 1, iy, s.seed);
    const double c = lattice_value(ix, iy + 1, s.seed), d = lattice_value(ix + 1, iy + 1, s.seed);
    return s.roughness_m * ((a * (1 - tx) + b * tx) * (1 - ty) + (c * (1 - tx) + d * tx) * ty);
}

HeightField rasterize(const TerrainSpec& s, const Rect& area, double res)
{
    const int nx = static_cast<int>(std::ceil((area.x1_m - area.x0_m) / res));
    const int ny = static_cast<int>(std::ceil((area.y1_m - area.y0_m) / res));
    HeightField f(area.x0_m, area.y0_m, res, nx, ny, static_cast<float>(s.ground_z_m));
    for (int i = 0; i < nx; ++i) {
        const double x = f.cell_x(i);
        for (int j = 0; j < ny; ++j) {
            const double y = f.cell_y(j);
            const double ground = s.ground_z_m + roughness_at(s, x, y);
            double z = ground;
            for (const RampSpec& r : s.ramps)
                if (r.area.contains(x, y)) z = std::max(z, ground + r.rise_m * std::clamp(ramp_fraction(r, x, y), 0.0, 1.0));
            for (const DitchSpec& d : s.ditches)
                if (d.area.contains(x, y)) z = std::min(z, ground - d.depth_m);
            for (const BoxSpec& b : s.boxes)
                if (b.area.contains(x, y)) z = std::max(z, s.ground_z_m + b.height_m);
            for (const WallSpec& w : s.walls)
                if (distance_to_segment(x, y, w) <= w.thickness_m / 2) z = std::max(z, s.ground_z_m + w.height_m);
            f.at(i, j) = static_cast<float>(z);
        }
    }
    return f;
}

}  // namespace ugv::simworld
