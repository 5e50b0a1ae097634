// The local ground written plainly, lattice point by lattice point: the specification the
// classifier's local_ground (moments by separable sums, outliers subtracted, a selection
// over a reused buffer) is tested against.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "local_ground.hpp"
#include "ugv/traverse/cell_classifier.hpp"

namespace ugv::traverse {

namespace {

// The plane z = a + gp p + gq q through points (offsets p, q; heights z) by least squares;
// with a previous fit, only the points within `band` of it. Flat (0, 0) with too few points.
PlaneFit fit_plane(const std::vector<float>& z, const std::vector<std::array<float, 2>>& pq, const PlaneFit* previous,
                   float band)
{
    PlaneMoments m;
    for (std::size_t u = 0; u < z.size(); ++u) {
        const double p = pq[u][0], q = pq[u][1], v = z[u];
        if (previous && std::abs(v - (previous->a + previous->gp * p + previous->gq * q)) > band) continue;
        m.s0 += 1;
        m.sp += p;
        m.sq += q;
        m.spp += p * p;
        m.sqq += q * q;
        m.spq += p * q;
        m.sz += v;
        m.spz += p * v;
        m.sqz += q * v;
    }
    return plane_from_moments(m, previous);
}

}  // namespace

void local_ground_reference(const TerrainGrid& g, const std::vector<uint8_t>& known,
                            const std::vector<uint8_t>& points, double radius_m, double max_step_m,
                            std::vector<float>& ground)
{
    constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
    const int nx = g.nx, ny = g.ny, h = ground_half_width(radius_m, g.resolution_m);
    const int lx = (nx - 1) / kGroundStride + 1, ly = (ny - 1) / kGroundStride + 1;
    std::vector<float> lattice(static_cast<std::size_t>(lx) * ly, kNaN);
    std::vector<std::array<float, 2>> lattice_slope(static_cast<std::size_t>(lx) * ly, {0.0f, 0.0f});
    std::vector<float> window;
    std::vector<std::array<float, 2>> offsets;
    for (int a = 0; a < lx; ++a)
        for (int b = 0; b < ly; ++b) {
            const int i = a * kGroundStride, j = b * kGroundStride;
            // The points of the window (every other row and column) and the plane through
            // them, fitted twice: the second time without the cells more than max_step/2 off the
            // first (an obstacle at the window's side would tilt it). Their heights less the
            // plane's slope are level; a low percentile of them is the ground.
            window.clear();
            offsets.clear();
            const float zc = g.mean_z_m[static_cast<std::size_t>(i) * ny + j];
            const float zref = std::isnan(zc) ? 0.0f : zc;
            for (int p = std::max(0, i - h); p <= std::min(nx - 1, i + h); p += 2)
                for (int q = std::max(0, j - h); q <= std::min(ny - 1, j + h); q += 2) {
                    const std::size_t m = static_cast<std::size_t>(p) * ny + q;
                    if (!points[m]) continue;
                    window.push_back(g.mean_z_m[m] - zref);
                    offsets.push_back({static_cast<float>(p - i), static_cast<float>(q - j)});
                }
            if (window.size() < 3) continue;
            PlaneFit fit = fit_plane(window, offsets, nullptr, 0.0f);
            fit = fit_plane(window, offsets, &fit, static_cast<float>(0.5 * max_step_m));
            for (std::size_t u = 0; u < window.size(); ++u)
                window[u] += zref - (fit.gp * offsets[u][0] + fit.gq * offsets[u][1]);
            const auto mid = window.begin() + static_cast<std::ptrdiff_t>(ground_rank(window.size()));
            std::nth_element(window.begin(), mid, window.end());
            lattice[static_cast<std::size_t>(a) * ly + b] = *mid;
            lattice_slope[static_cast<std::size_t>(a) * ly + b] = {fit.gp, fit.gq};
        }
    interpolate_ground(g, known, lattice, lattice_slope, ground);
}

}  // namespace ugv::traverse
