#include "ugv/traverse/terrain_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace ugv::traverse {

Eigen::Vector2d TerrainGrid::cell_centre_body(int i, int j) const
{
    // Map coordinates are body coordinates turned by +residual_yaw (map axes = body axes
    // turned by -residual_yaw).
    const double mx = origin_x_m + (i + 0.5) * resolution_m;
    const double my = origin_y_m + (j + 0.5) * resolution_m;
    const double c = std::cos(residual_yaw_rad), s = std::sin(residual_yaw_rad);
    return {c * mx + s * my, -s * mx + c * my};
}

namespace {

// Whether any cell fails the per-cell checks of check_grid (which then finds the first and
// says why): the same tests four cells at a time, without a branch (GCC/Clang vector
// extensions). x - x is 0 for a finite x, NaN for an infinity or NaN.
bool any_bad_cell(const TerrainGrid& g)
{
    using F4 = float __attribute__((vector_size(16)));
    using I4 = int32_t __attribute__((vector_size(16)));
    const std::size_t n = g.cells();
    const bool have_age = !g.age_s.empty();
    // Four cells from k; past the end, fill (an unknown cell: count 0, mean NaN, passes).
    const auto load = [n](const auto* p, std::size_t k, auto fill, bool whole) {
        decltype(fill) v = fill;
        if (whole)
            std::memcpy(&v, p + k, sizeof v);
        else
            for (std::size_t e = k; e < n; ++e) v[e - k] = p[e];
        return v;
    };
    const F4 zero = {0, 0, 0, 0}, nan = {NAN, NAN, NAN, NAN};
    const I4 izero = {0, 0, 0, 0};
    const auto test = [&](std::size_t k, bool whole) {
        const I4 count = load(g.count.data(), k, izero, whole);
        const F4 mean = load(g.mean_z_m.data(), k, nan, whole), hi = load(g.max_z_m.data(), k, zero, whole);
        const F4 lo = load(g.min_z_m.data(), k, zero, whole), var = load(g.variance_z_m2.data(), k, zero, whole);
        const F4 age = have_age ? load(g.age_s.data(), k, zero, whole) : zero;
        const I4 known = (count != izero) & (mean == mean);
        const I4 finite = (mean - mean == zero) & (hi - hi == zero) & (lo - lo == zero);
        const I4 variance_ok = ~(var < zero) & ((var - var == zero) | (var != var));
        const I4 age_ok = ~(age < zero) & ((age - age == zero) | (age != age));
        return (count < izero) | (known & ~(finite & ~(hi < lo) & variance_ok & age_ok));
    };
    I4 bad = izero;
    std::size_t k = 0;
    for (; k + 4 <= n; k += 4) bad |= test(k, true);
    if (k < n) bad |= test(k, false);
    return (bad[0] | bad[1] | bad[2] | bad[3]) != 0;
}

}  // namespace

std::string check_grid(const TerrainGrid& g)
{
    constexpr long long kMaxCells = 4'000'000;
    if (g.nx <= 0 || g.ny <= 0) return "nx or ny not positive";
    if (static_cast<long long>(g.nx) * g.ny > kMaxCells) return "more than 4 million cells";
    if (!(std::isfinite(g.resolution_m) && g.resolution_m > 0)) return "resolution not finite and positive";
    if (!std::isfinite(g.origin_x_m) || !std::isfinite(g.origin_y_m)) return "origin not finite";
    if (!std::isfinite(g.residual_yaw_rad) || std::abs(g.residual_yaw_rad) > 3.5) return "residual_yaw not an angle";
    if (!g.position_m.allFinite()) return "pose position not finite";
    if (g.utime_us <= 0) return "utime not positive";
    const std::size_t n = g.cells();
    if (g.mean_z_m.size() != n || g.variance_z_m2.size() != n || g.max_z_m.size() != n || g.min_z_m.size() != n ||
        g.count.size() != n)
        return "a layer's length is not nx * ny";
    if (!g.age_s.empty() && g.age_s.size() != n) return "age_s's length is not nx * ny";
    if (!any_bad_cell(g)) return {};
    for (std::size_t k = 0; k < n; ++k) {
        if (g.count[k] < 0) return "negative count";
        if (g.count[k] == 0 || std::isnan(g.mean_z_m[k])) continue;  // unknown
        if (!std::isfinite(g.mean_z_m[k]) || !std::isfinite(g.max_z_m[k]) || !std::isfinite(g.min_z_m[k]))
            return "a known cell with a non-finite mean, max or min";
        if (g.max_z_m[k] < g.min_z_m[k]) return "a known cell with max below min";
        if (g.variance_z_m2[k] < 0 || std::isinf(g.variance_z_m2[k])) return "a known cell with a negative or infinite variance";
        if (!g.age_s.empty() && (g.age_s[k] < 0 || std::isinf(g.age_s[k]))) return "a known cell with a negative or infinite age";
    }
    return {};
}

}  // namespace ugv::traverse
