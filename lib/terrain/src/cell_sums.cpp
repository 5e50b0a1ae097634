#include "ugv/terrain/cell_sums.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ugv::terrain {

// sum w (z - ref) = wz + w d,  sum w (z - ref)^2 = wz2 + 2 d wz + w d^2,  d = z_ref - ref.
void z_sums_about(const CellSums& c, double ref_m, double& wz, double& wz2)
{
    wz = 0.0;
    wz2 = 0.0;
    if (c.empty()) return;
    const double d = static_cast<double>(c.z_ref_m) - ref_m;
    wz = c.z_wz + c.w * d;
    wz2 = c.z_wz2 + 2.0 * d * c.z_wz + c.w * d * d;
}

void add_sums(CellSums& a, const CellSums& b)
{
    if (b.empty()) return;
    if (a.empty()) {
        a = b;
        return;
    }
    double wz = 0.0, wz2 = 0.0;
    z_sums_about(b, a.z_ref_m, wz, wz2);
    a.w += b.w;
    a.x_wx += b.x_wx;
    a.y_wy += b.y_wy;
    a.z_wz = static_cast<float>(a.z_wz + wz);
    a.x_wx2 += b.x_wx2;
    a.y_wy2 += b.y_wy2;
    a.z_wz2 = static_cast<float>(a.z_wz2 + wz2);
}

void move_reference(CellSums& c, double ref_m)
{
    const float ref = static_cast<float>(ref_m);
    if (c.empty()) {
        c.z_ref_m = ref;
        c.w = 0.0f;
        return;
    }
    double wz = 0.0, wz2 = 0.0;
    z_sums_about(c, ref, wz, wz2);
    c.z_ref_m = ref;
    c.z_wz = static_cast<float>(wz);
    c.z_wz2 = static_cast<float>(std::max(0.0, wz2));
}

void recentre(CellSums& c)
{
    if (c.empty() || !(c.w > 0.0f)) return;
    move_reference(c, c.z_ref_m + static_cast<double>(c.z_wz) / c.w);
}

CellStatistics cell_statistics(const CellSums& c, StatisticsKind kind)
{
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    if (c.empty() || !(c.w > 0.0f)) return {nan, nan};
    const double w = c.w, wz = c.z_wz, wz2 = c.z_wz2;
    const double mean_rel = wz / w;
    const double mean = c.z_ref_m + mean_rel;
    if (kind == StatisticsKind::classical) {
        // With unit weights w is N (spread samples carry fractions of 1).
        if (!(w > 1.0)) return {mean, nan};
        const double spread = wz2 - wz * mean_rel;  // sum dz^2 - N mean_dz^2
        return {mean, std::max(0.0, spread) / (w - 1.0)};
    }
    const double numerator = w * wz2 - wz * wz;
    return {mean, std::max(0.0, numerator) / (w * w)};
}

void mean_offset(const CellSums& c, float& x_re_m, float& y_re_m)
{
    x_re_m = c.w > 0.0f ? c.x_wx / c.w : 0.0f;  // false for an empty cell's NaN
    y_re_m = c.w > 0.0f ? c.y_wy / c.w : 0.0f;
}

}  // namespace ugv::terrain
