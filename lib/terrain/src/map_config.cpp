#include <stdexcept>
#include <string>

#include "ugv/terrain/map_config.hpp"

namespace ugv::terrain {

void MapConfig::validate() const
{
    auto fail = [](const char* field, const char* why) {
        throw std::invalid_argument(std::string(field) + ": " + why);
    };
    if (!(grid_size_m >= 0.01 && grid_size_m <= 10.0)) fail("grid_size_m", "must be in [0.01, 10] m");
    if (!(extent_x_m >= grid_size_m && extent_x_m <= 1000.0)) fail("extent_x_m", "must be in [grid_size_m, 1000] m");
    if (!(extent_y_m >= grid_size_m && extent_y_m <= 1000.0)) fail("extent_y_m", "must be in [grid_size_m, 1000] m");
    if (static_cast<double>(nx()) * ny() > 4.0e6) fail("extent_x_m", "more than 4 million cells");
    if (!(theta_d_rad > 0.0 && theta_d_rad <= M_PI)) fail("theta_d_rad", "must be in (0, pi]");
    if (spread_max_cells < 1 || spread_max_cells > kMaxSpreadCells) fail("spread_max_cells", "must be in [1, 4]");
    if (!(min_variance_m2 > 0.0 && min_variance_m2 < 1.0)) fail("min_variance_m2", "must be in (0, 1) m^2");
    if (pose_history_us <= 0) fail("pose_history_us", "must be positive");
    if (!(max_interpolation_span_s > 0.0)) fail("max_interpolation_span_s", "must be positive");
    if (!(std::isfinite(reference_x_m) && std::isfinite(reference_y_m))) fail("reference_x_m", "must be finite");
    if (statistics != StatisticsKind::variance_weighted && statistics != StatisticsKind::classical)
        fail("statistics", "unknown kind");
    if (spread_form != SpreadForm::exact && spread_form != SpreadForm::summed_area && spread_form != SpreadForm::centred)
        fail("spread_form", "unknown form");
    if (mode != MapMode::egocentric && mode != MapMode::world_aligned) fail("mode", "unknown mode");
}

}  // namespace ugv::terrain
