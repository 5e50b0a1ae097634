#include "local_ground.hpp"

#include <algorithm>
#include <limits>

namespace ugv::traverse {

void interpolate_ground(const TerrainGrid& g, const std::vector<uint8_t>& known, const std::vector<float>& lattice,
                        const std::vector<std::array<float, 2>>& lattice_slope, std::vector<float>& ground)
{
    constexpr int kStride = kGroundStride;
    const int nx = g.nx, ny = g.ny;
    const int lx = (nx - 1) / kStride + 1, ly = (ny - 1) / kStride + 1;
    ground.assign(g.cells(), std::numeric_limits<float>::quiet_NaN());
    for (int i = 0; i < nx; ++i) {
        const int a = std::min(i / kStride, lx - 1), a1 = std::min(a + 1, lx - 1);
        const float fa = static_cast<float>(i - a * kStride) / kStride;
        for (int j = 0; j < ny; ++j) {
            const std::size_t k = static_cast<std::size_t>(i) * ny + j;
            if (!known[k]) continue;
            const int b = std::min(j / kStride, ly - 1), b1 = std::min(b + 1, ly - 1);
            const float fb = static_cast<float>(j - b * kStride) / kStride;
            // Each corner's level carried to the cell along its plane, blended bilinearly over
            // the corners that have one.
            float sum = 0, weight = 0;
            const int ca[4] = {a, a1, a, a1}, cb[4] = {b, b, b1, b1};
            const float wc[4] = {(1 - fa) * (1 - fb), fa * (1 - fb), (1 - fa) * fb, fa * fb};
            for (int u = 0; u < 4; ++u) {
                const std::size_t l = static_cast<std::size_t>(ca[u]) * ly + cb[u];
                if (std::isnan(lattice[l]) || wc[u] <= 0) continue;
                const float level = lattice[l] + lattice_slope[l][0] * static_cast<float>(i - ca[u] * kStride) +
                                    lattice_slope[l][1] * static_cast<float>(j - cb[u] * kStride);
                sum += wc[u] * level;
                weight += wc[u];
            }
            if (weight > 1e-3f) ground[k] = sum / weight;
        }
    }
}

void interpolate_ground_squares(const TerrainGrid& g, const std::vector<uint8_t>& known,
                                const std::vector<uint8_t>& square_known, const std::vector<float>& lattice,
                                const std::vector<std::array<float, 2>>& lattice_slope, std::vector<float>& ground)
{
    // GCC/Clang vector extensions; each lane is the scalar expression's IEEE result.
    using F4 = float __attribute__((vector_size(16)));
    constexpr int kStride = kGroundStride;
    const int nx = g.nx, ny = g.ny;
    const int lx = (nx - 1) / kStride + 1, ly = (ny - 1) / kStride + 1;
    const std::size_t w = static_cast<std::size_t>(ny);
    ground.assign(g.cells(), std::numeric_limits<float>::quiet_NaN());
    // Lanes: the cells j = 3 b + dj, dj = 0, 1, 2 (lane 3 unused).
    const F4 dj = {0.0f, 1.0f, 2.0f, 0.0f};
    const F4 fb = {0.0f / kStride, 1.0f / kStride, 2.0f / kStride, 0.0f};
    const F4 one = {1.0f, 1.0f, 1.0f, 1.0f}, zero = {0, 0, 0, 0};
    const F4 min_weight = {1e-3f, 1e-3f, 1e-3f, 1e-3f};
    const F4 nan4 = {NAN, NAN, NAN, NAN};
    for (int a = 0; a < lx; ++a) {
        const int a1 = std::min(a + 1, lx - 1);
        for (int b = 0; b < ly; ++b) {
            if (!square_known[static_cast<std::size_t>(a) * ly + b]) continue;
            const int b1 = std::min(b + 1, ly - 1);
            const int ca[4] = {a, a1, a, a1}, cb[4] = {b, b, b1, b1};
            for (int i = a * kStride; i < std::min(nx, (a + 1) * kStride); ++i) {
                const float fa = static_cast<float>(i - a * kStride) / kStride;
                // The corners' weights, in interpolate_ground's order and expressions.
                const F4 fa4 = {fa, fa, fa, fa};
                const F4 wc[4] = {(one - fa4) * (one - fb), fa4 * (one - fb), (one - fa4) * fb, fa4 * fb};
                F4 sum = zero, weight = zero;
                for (int u = 0; u < 4; ++u) {
                    const std::size_t l = static_cast<std::size_t>(ca[u]) * ly + cb[u];
                    if (std::isnan(lattice[l])) continue;
                    // level = (lattice + slope_i di) + slope_j dj, as the scalar expression.
                    const float row = lattice[l] + lattice_slope[l][0] * static_cast<float>(i - ca[u] * kStride);
                    const float s1 = lattice_slope[l][1], dj0 = static_cast<float>(b * kStride - cb[u] * kStride);
                    const F4 row4 = {row, row, row, row}, s14 = {s1, s1, s1, s1}, dj04 = {dj0, dj0, dj0, dj0};
                    // A lane whose weight is 0 (skipped by interpolate_ground) adds +-0 to sums
                    // that are never -0 (the level is finite): no change.
                    const F4 level = row4 + s14 * (dj04 + dj);
                    sum += wc[u] * level;
                    weight += wc[u];
                }
                const F4 value = weight > min_weight ? sum / weight : nan4;
                const std::size_t row_start = static_cast<std::size_t>(i) * w;
                for (int e = 0; e < kStride && b * kStride + e < ny; ++e) {
                    const std::size_t k = row_start + static_cast<std::size_t>(b * kStride + e);
                    if (known[k]) ground[k] = value[e];
                }
            }
        }
    }
}

}  // namespace ugv::traverse
