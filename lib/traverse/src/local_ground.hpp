// The pieces of the local ground (docs/traverse.md, section 1, step 4) that the classifier's
// fast local_ground and local_ground_reference share: the lattice, the plane from its
// moments, the percentile's rank and the interpolation between lattice points.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "ugv/traverse/terrain_grid.hpp"

namespace ugv::traverse {

constexpr int kGroundStride = 3;  // a lattice point every third cell

// A radius as the half-width of the square window of cells it covers (at least 1). The
// resolution comes from a float (0.2f is 0.2000000030): a radius of a whole number of cells
// must still cover them all, so the tolerance is above float's rounding.
inline int ground_half_width(double radius_m, double resolution_m)
{
    return std::max(1, static_cast<int>(std::floor(radius_m / resolution_m + 1e-6)));
}

// The rank of the ground among n levelled heights: the 40th percentile.
inline std::size_t ground_rank(std::size_t n) { return 2 * n / 5; }

// Sums over a window's points of 1, p, q, pp, qq, pq, z, pz, qz (p, q: offsets in cells).
struct PlaneMoments
{
    double s0 = 0, sp = 0, sq = 0, spp = 0, sqq = 0, spq = 0, sz = 0, spz = 0, sqz = 0;
};

struct PlaneFit
{
    float a = 0, gp = 0, gq = 0;  // z = a + gp p + gq q
};

// The least-squares plane of the moments; with fewer than 6 points, the previous fit (or
// flat through 0 without one); level (gp = gq = 0) when the points lie (nearly) on a line.
inline PlaneFit plane_from_moments(const PlaneMoments& m, const PlaneFit* previous)
{
    PlaneFit f;
    if (m.s0 < 6) return previous ? *previous : f;
    const double s0 = m.s0;
    const double cpp = m.spp - m.sp * m.sp / s0, cqq = m.sqq - m.sq * m.sq / s0, cpq = m.spq - m.sp * m.sq / s0;
    const double cpz = m.spz - m.sp * m.sz / s0, cqz = m.sqz - m.sq * m.sz / s0, det = cpp * cqq - cpq * cpq;
    if (det > 1e-6 * s0 * s0) {
        f.gp = static_cast<float>((cqq * cpz - cpq * cqz) / det);
        f.gq = static_cast<float>((cpp * cqz - cpq * cpz) / det);
    }
    f.a = static_cast<float>((m.sz - f.gp * m.sp - f.gq * m.sq) / s0);
    return f;
}

// ground := each known cell's level: each lattice corner's level carried to the cell along
// its plane, blended bilinearly over the corners that have one; NaN elsewhere.
void interpolate_ground(const TerrainGrid& g, const std::vector<uint8_t>& known, const std::vector<float>& lattice,
                        const std::vector<std::array<float, 2>>& lattice_slope, std::vector<float>& ground);

// interpolate_ground, the same floats, a lattice square at a time: the three cells of a
// square's row in one vector (they share the square's corners). square_known: per square
// (a * ly + b), whether it holds a known cell (the others are left NaN).
void interpolate_ground_squares(const TerrainGrid& g, const std::vector<uint8_t>& known,
                                const std::vector<uint8_t>& square_known, const std::vector<float>& lattice,
                                const std::vector<std::array<float, 2>>& lattice_slope, std::vector<float>& ground);

}  // namespace ugv::traverse
