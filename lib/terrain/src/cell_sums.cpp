#include "ugv/terrain/cell_sums.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ugv::terrain {

void add_sums(CellSums& a, const CellSums& b)
{
    a.z_w += b.z_w;
    a.z_wz += b.z_wz;
    a.z_wz2 += b.z_wz2;
    a.x_w += b.x_w;
    a.x_wx += b.x_wx;
    a.x_wx2 += b.x_wx2;
    a.y_w += b.y_w;
    a.y_wy += b.y_wy;
    a.y_wy2 += b.y_wy2;
    a.n += b.n;
}

CellStatistics cell_statistics(const CellSums& c, StatisticsKind kind)
{
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    if (c.n == 0 || !(c.z_w > 0.0)) return {nan, nan};
    const double mean = c.z_wz / c.z_w;
    if (kind == StatisticsKind::classical) {
        // With unit weights z_w is N (spread samples carry fractions of 1).
        if (!(c.z_w > 1.0)) return {mean, nan};
        const double spread = c.z_wz2 - c.z_wz * mean;  // sum z^2 - N mean^2
        return {mean, std::max(0.0, spread) / (c.z_w - 1.0)};
    }
    const double numerator = c.z_w * c.z_wz2 - c.z_wz * c.z_wz;
    return {mean, std::max(0.0, numerator) / (c.z_w * c.z_w)};
}

void mean_offset(const CellSums& c, float& x_re_m, float& y_re_m)
{
    x_re_m = c.x_w > 0.0f ? c.x_wx / c.x_w : 0.0f;
    y_re_m = c.y_w > 0.0f ? c.y_wy / c.y_w : 0.0f;
}

}  // namespace ugv::terrain
