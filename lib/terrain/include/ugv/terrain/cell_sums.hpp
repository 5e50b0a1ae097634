// One grid element: the ten sums of the report's Table 1, and the statistics they give.
//
// x and y are kept relative to the centre of the cell that holds them (the remainder of
// eq. 9-10 / 15-16), so float is enough for them; z is absolute height (ENU up, m) and its
// sums are double, so that eq. 32, which subtracts two nearly equal products, cannot go
// negative through rounding (it is clamped at 0 for the last ulp).
#pragma once

#include <cstdint>

namespace ugv::terrain {

enum class StatisticsKind : int8_t {
    variance_weighted = 0,  // eq. 23 (mean) and eq. 32 (variance)
    classical = 1,          // eq. 21 (mean) and eq. 22 (variance, N - 1)
};

struct alignas(64) CellSums
{
    double z_w = 0.0;     // Table 1 #8:  sum 1/s_z^2          (1/m^2)
    double z_wz = 0.0;    // Table 1 #10: sum z/s_z^2          (1/m)
    double z_wz2 = 0.0;   // Table 1 #9:  sum z^2/s_z^2        (1)
    float x_w = 0.0f;     // Table 1 #2:  sum 1/s_x^2
    float x_wx = 0.0f;    // Table 1 #4:  sum x/s_x^2, x from the cell centre
    float x_wx2 = 0.0f;   // Table 1 #3:  sum x^2/s_x^2
    float y_w = 0.0f;     // Table 1 #5
    float y_wy = 0.0f;    // Table 1 #7
    float y_wy2 = 0.0f;   // Table 1 #6
    uint32_t n = 0;       // Table 1 #1:  samples fused (a spread sample counts in each cell it touches)

    bool empty() const { return n == 0; }
};

// Fuses one sample: (x_rel_m, y_rel_m) from the cell centre, z_m, with weight w = 1/s^2
// (1/m^2; the classical statistics fuse with w = 1). Inline: this is the hot loop.
inline void fuse_sample(CellSums& c, float x_rel_m, float y_rel_m, double z_m, float w)
{
    const double wd = w;
    c.z_w += wd;
    c.z_wz += wd * z_m;
    c.z_wz2 += wd * z_m * z_m;
    const float wx = w * x_rel_m;
    c.x_w += w;
    c.x_wx += wx;
    c.x_wx2 += wx * x_rel_m;
    const float wy = w * y_rel_m;
    c.y_w += w;
    c.y_wy += wy;
    c.y_wy2 += wy * y_rel_m;
    ++c.n;
}

// Adds every sum of b into a (the working map of the rotation, eq. 9-16).
void add_sums(CellSums& a, const CellSums& b);

struct CellStatistics
{
    double mean_z_m;       // NaN when the cell is empty
    double variance_z_m2;  // NaN when empty (and, classical, when fewer than 2 samples)
};

// Variance weighted: mean = sum(z/s2)/sum(1/s2) (eq. 23),
//   variance = (sum(1/s2) sum(z^2/s2) - sum(z/s2)^2) / sum(1/s2)^2 (eq. 32).
// Classical (sums fused with w = 1, so sum(1/s2) = N): mean = sum z / N (eq. 21),
//   variance = (sum z^2 - N mean^2) / (N - 1) (eq. 22).
CellStatistics cell_statistics(const CellSums& c, StatisticsKind kind);

// Mean horizontal position of the cell's samples relative to the cell centre (m): the
// remainder (x_re, y_re) of eq. 9-10. (0, 0) when the sums hold no weight.
void mean_offset(const CellSums& c, float& x_re_m, float& y_re_m);

}  // namespace ugv::terrain
