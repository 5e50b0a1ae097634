// One grid element: the sums of the report's Table 1, and the statistics they give.
//
// 32 bytes, half a cache line, all float, so that the fusion loop touches little memory:
// - One weight sum for x, y and z: a point's error region is a sphere (eq. 19-20), so the
//   same 1/s^2 weighs its x, y and z and Table 1's sums #2, #5 and #8 are one number.
// - x and y are kept relative to the centre of the cell that holds them (the remainder of
//   eq. 9-10 / 15-16), so they are small.
// - z is kept relative to the cell's own reference height z_ref_m, so the z sums hold
//   deviations of centimetres, not ENU heights of hundreds of metres: float then suffices
//   for eq. 32, which subtracts two nearly equal products (tested against a double
//   reference at 750 m with millimetre noise in test_cell_precision). The reference is the
//   first sample, moved to any later sample that outweighs all before it: the float
//   rounding is relative to sum w (z - ref)^2, so a light first sample far from the rest
//   must not stay the reference.
// The sample count N (Table 1 #1) is kept by the grid beside the cells (CellArray).
#pragma once

#include <cstdint>
#include <limits>

namespace ugv::terrain {

enum class StatisticsKind : int8_t {
    variance_weighted = 0,  // eq. 23 (mean) and eq. 32 (variance)
    classical = 1,          // eq. 21 (mean) and eq. 22 (variance, N - 1)
};

// The order of the fields lets the fusion loop add a sample with two 4-float vector adds
// (src/cell_fusion.hpp).
struct alignas(32) CellSums
{
    // NaN while the cell is empty, so that one comparison (!(w <= c.w)) tells the fusion
    // loop that the cell is empty or that a new sample outweighs it.
    float w = std::numeric_limits<float>::quiet_NaN();  // Table 1 #2, #5, #8: sum 1/s^2 (1/m^2)
    float x_wx = 0.0f;    // Table 1 #4:  sum x/s^2, x from the cell centre
    float y_wy = 0.0f;    // Table 1 #7
    float z_wz = 0.0f;    // Table 1 #10: sum z/s^2, z from z_ref_m
    float z_ref_m = std::numeric_limits<float>::quiet_NaN();  // ENU height the z sums are taken from; NaN: empty
    float x_wx2 = 0.0f;   // Table 1 #3:  sum x^2/s^2
    float y_wy2 = 0.0f;   // Table 1 #6
    float z_wz2 = 0.0f;   // Table 1 #9

    bool empty() const { return z_ref_m != z_ref_m; }
};
static_assert(sizeof(CellSums) == 32);

// Moves the cell's reference height to ref_m (sums re-expressed in double); an empty cell
// just takes it.
void move_reference(CellSums& c, double ref_m);

// Fuses one sample: (x_rel_m, y_rel_m) from the cell centre, z_m (ENU height), with weight
// w = 1/s^2 (1/m^2; the classical statistics fuse with w = 1). Inline: this is the hot loop.
inline void fuse_sample(CellSums& c, float x_rel_m, float y_rel_m, double z_m, float w)
{
    if (!(w <= c.w)) move_reference(c, z_m);  // empty (w is NaN) or outweighed: rare once a cell holds a few samples
    const float dz = static_cast<float>(z_m - static_cast<double>(c.z_ref_m));
    const float wx = w * x_rel_m;
    const float wy = w * y_rel_m;
    const float wz = w * dz;
    c.w += w;
    c.x_wx += wx;
    c.y_wy += wy;
    c.z_wz += wz;
    c.x_wx2 += wx * x_rel_m;
    c.y_wy2 += wy * y_rel_m;
    c.z_wz2 += wz * dz;
}

// Adds every sum of b into a, b's z sums re-expressed about a's reference height (cells
// that land in the same cell in a rotation, eq. 9-16).
void add_sums(CellSums& a, const CellSums& b);

// Moves the cell's reference height to its weighted mean (the z sums are re-expressed in
// double): afterwards the z sums hold only the spread about the mean.
void recentre(CellSums& c);

// The cell's z sums (#10 and #9) about height ref_m instead of z_ref_m, in double
// (ref_m = 0: the sums of ENU heights). 0 for an empty cell.
void z_sums_about(const CellSums& c, double ref_m, double& wz, double& wz2);

struct CellStatistics
{
    double mean_z_m;       // NaN when the cell is empty
    double variance_z_m2;  // NaN when empty (and, classical, when fewer than 2 samples)
};

// Variance weighted: mean = sum(z/s2)/sum(1/s2) (eq. 23),
//   variance = (sum(1/s2) sum(z^2/s2) - sum(z/s2)^2) / sum(1/s2)^2 (eq. 32).
// Classical (sums fused with w = 1, so sum(1/s2) = N): mean = sum z / N (eq. 21),
//   variance = (sum z^2 - N mean^2) / (N - 1) (eq. 22).
// Both are evaluated in double on the sums about z_ref_m (a shift changes neither variance).
CellStatistics cell_statistics(const CellSums& c, StatisticsKind kind);

// Mean horizontal position of the cell's samples relative to the cell centre (m): the
// remainder (x_re, y_re) of eq. 9-10. (0, 0) when the sums hold no weight.
void mean_offset(const CellSums& c, float& x_re_m, float& y_re_m);

}  // namespace ugv::terrain
