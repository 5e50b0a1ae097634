#include "ugv/terrain/evaluation.hpp"

#include <cmath>

namespace ugv::terrain {

Eigen::Vector2d cell_centre_world(const MapSnapshot& m, int i, int j)
{
    // Map axes are the body's turned by -residual_yaw, i.e. at world yaw (yaw - residual).
    const double mx = m.origin_x_m + (i + 0.5) * m.resolution_m;
    const double my = m.origin_y_m + (j + 0.5) * m.resolution_m;
    const double axis_yaw = m.pose.yaw_rad() - m.residual_yaw_rad;
    const double c = std::cos(axis_yaw), s = std::sin(axis_yaw);
    return m.pose.position_m.head<2>() + Eigen::Vector2d(c * mx - s * my, s * mx + c * my);
}

MapMetrics evaluate(const MapSnapshot& m, const std::function<double(double, double)>& truth, double obstacle_height_m,
                    const std::function<double(double, double)>& ground)
{
    MapMetrics r;
    double sum = 0.0, sum2 = 0.0, var_sum = 0.0;
    int var_n = 0;
    const std::size_t cells = static_cast<std::size_t>(m.nx) * static_cast<std::size_t>(m.ny);
    const bool have_max = m.max_z_m.size() >= cells;
    double max_sum = 0.0, max_sum2 = 0.0, obstacle_mean_sum = 0.0, obstacle_max_sum = 0.0;
    int max_n = 0;
    for (int i = 0; i < m.nx; ++i) {
        for (int j = 0; j < m.ny; ++j) {
            const Eigen::Vector2d w = cell_centre_world(m, i, j);
            const double t = truth(w.x(), w.y());
            if (!std::isfinite(t)) continue;
            ++r.cells;
            const std::size_t k = static_cast<std::size_t>(i * m.ny + j);
            const double z = m.mean_z_m[k];
            if (!std::isfinite(z)) continue;
            ++r.known;
            const double e = z - t;
            sum += e;
            sum2 += e * e;
            if (std::isfinite(m.variance_z_m2[k])) {
                var_sum += m.variance_z_m2[k];
                ++var_n;
            }
            double g = ground ? ground(w.x(), w.y()) : 0.0;
            if (!std::isfinite(g)) g = t;
            // 1e-5: true heights are float32 (a 0.2 m box on ground at 1.5 m stands 0.19999999 m).
            const bool obstacle = t - g >= obstacle_height_m - 1e-5;
            const bool seen = z - g > 0.5 * obstacle_height_m;
            r.obstacle_cells += obstacle ? 1 : 0;
            r.obstacles_detected += obstacle && seen ? 1 : 0;
            r.false_obstacles += !obstacle && seen ? 1 : 0;
            if (obstacle) obstacle_mean_sum += e;
            const double top = have_max ? static_cast<double>(m.max_z_m[k]) : NAN;
            if (std::isfinite(top)) {
                ++max_n;
                max_sum += top - t;
                max_sum2 += (top - t) * (top - t);
                if (obstacle) obstacle_max_sum += top - t;
            }
        }
    }
    if (max_n > 0) {
        r.max_bias_m = max_sum / max_n;
        r.max_rmse_m = std::sqrt(max_sum2 / max_n);
    }
    if (r.obstacle_cells > 0) {
        r.obstacle_mean_error_m = obstacle_mean_sum / r.obstacle_cells;
        if (max_n > 0) r.obstacle_max_error_m = obstacle_max_sum / r.obstacle_cells;
    }
    if (r.cells > 0) r.coverage = static_cast<double>(r.known) / r.cells;
    if (r.known > 0) {
        r.bias_m = sum / r.known;
        r.rmse_m = std::sqrt(sum2 / r.known);
    }
    if (var_n > 0) r.mean_cell_variance_m2 = var_sum / var_n;
    return r;
}

AreaCoverage area_coverage(const MapSnapshot& m, const BodyArea& area)
{
    AreaCoverage r;
    // Map axes are the body's turned by -residual_yaw (cell_centre_world).
    const double c = std::cos(m.residual_yaw_rad), s = std::sin(m.residual_yaw_rad);
    const std::size_t cells = static_cast<std::size_t>(m.nx) * static_cast<std::size_t>(m.ny);
    if (m.mean_z_m.size() < cells) return r;
    for (int i = 0; i < m.nx; ++i) {
        const double mx = m.origin_x_m + (i + 0.5) * m.resolution_m;
        for (int j = 0; j < m.ny; ++j) {
            const double my = m.origin_y_m + (j + 0.5) * m.resolution_m;
            const double bx = c * mx + s * my, by = -s * mx + c * my;
            if (bx < area.x0_m || bx > area.x1_m || std::abs(by) > area.half_width_m) continue;
            ++r.cells;
            if (std::isfinite(m.mean_z_m[static_cast<std::size_t>(i) * static_cast<std::size_t>(m.ny) +
                                         static_cast<std::size_t>(j)]))
                ++r.known;
        }
    }
    if (r.cells > 0) r.coverage = static_cast<double>(r.known) / r.cells;
    return r;
}

}  // namespace ugv::terrain
