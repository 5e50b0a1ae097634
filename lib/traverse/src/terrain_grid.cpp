#include "ugv/traverse/terrain_grid.hpp"

#include <cmath>

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
