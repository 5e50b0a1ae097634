// The fusion loop's inner parts, written with vectors (GCC/Clang vector extensions: SSE on
// x86-64 without -march, NEON on ARM, scalar code elsewhere; AVX2 where the CPU has it,
// kernel_table.hpp). Private to the library.
//
// place_math / place_points / place_chunk: points from the body frame into the map (the
//   end transforms of the scan blended at each point's time), eq. 19 variance, weight,
//   cell, offset from the cell centre, and what to do with each point; no branch. The
//   samples then go into the cells on the map's side (cell_fusion.hpp).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

#include "float4.hpp"
#include "float8.hpp"

namespace ugv::terrain::detail {

// The smallest and largest value of v[0 .. n-1], NaN skipped (an infinity is kept, so a
// batch with one makes an infinite span). A scalar loop does not vectorise: without
// -ffast-math float min/max is not reassociated.
inline void value_range(const float* v, std::size_t n, float& lo, float& hi)
{
    constexpr float inf = std::numeric_limits<float>::infinity();
    Float4 lo4 = splat(inf), hi4 = splat(-inf);
    std::size_t k = 0;
    for (; k + 4 <= n; k += 4) {
        const Float4 t = load4(v + k);
        lo4 = t < lo4 ? t : lo4;  // minps; NaN in t: lo4 stays
        hi4 = t > hi4 ? t : hi4;
    }
    for (; k < n; ++k) {
        lo4[0] = std::min(lo4[0], v[k]);  // NaN in v[k]: lo4 stays (std::min returns its first argument)
        hi4[0] = std::max(hi4[0], v[k]);
    }
    lo = std::min(std::min(lo4[0], lo4[1]), std::min(lo4[2], lo4[3]));
    hi = std::max(std::max(hi4[0], hi4[1]), std::max(hi4[2], hi4[3]));
}


// Everything place_points needs, broadcast once per batch to vectors of type V.
template <class V>
struct PlacementOf
{
    // Body -> map for the scan: row r of the transform at time fraction f is
    // (at_start[4r + c] + f * change[4r + c]) for the x, y, z coefficients c = 0..2 and the
    // offset c = 3; row 2 gives the ENU height.
    V at_start[12], change[12];
    V t_min_s, inv_span_per_s;            // f = (t - t_min) * inv_span
    V error_at_start_rad2, error_change_rad2;  // eq. 19's de^2, blended like the transform
    V min_variance_m2, inverse_scale, unit_weight;  // w = inverse_scale / s2 + unit_weight
    V spread_above_m2;                    // s2 above this: spread (section 3.5)
    V inv_g, g, y_min_m, nx, ny, nx_last, ny_last;
    V row_shift, column_shift;            // the grid's ring offsets, in cells
    V ring_rows, ring_columns;            // cells around each ring
    V row_stride;                         // cells per physical row
};
using Placement = PlacementOf<Float4>;

// Per point of a chunk: where it goes and with what.
struct PlacedPoints
{
    static constexpr std::size_t kCapacity = 64;
    alignas(16) float lx[kCapacity], ly[kCapacity], lz[kCapacity];  // map frame (m), ENU height
    alignas(16) float variance_m2[kCapacity], weight[kCapacity];
    alignas(16) int32_t cell[kCapacity], fuse[kCapacity];  // fuse: -1 for a plain point, 0 for a rare one
    int32_t all_fuse[kCapacity / 4];  // per group of four: every point is a plain one
    alignas(16) float sample[kCapacity][4];  // {0, x from the cell centre, y from it, z}: fuse_point_into's input
};

// What place_math works out for a vector of points (one point a lane).
template <class V, class I>
struct PlacedVector
{
    V l[3];          // map frame x, y (m) and ENU height
    V variance_m2;   // eq. 19-20, at least min_variance_m2
    V weight;
    V x_rel, y_rel;  // from the centre of the cell
    I cell;          // physical cell index
    I fuse;          // -1: fused here; 0: a rare point (invalid, outside or spread), sorted out by the caller
};

// The transform into the map (the end transforms of the scan blended at each point's
// time), eq. 19 variance, weight, cell, offset from the cell centre, and what to do with
// each point; no branch. Both grids' rows and columns are rings. Everything by reference and no helper calls, so that with 8-float vectors it is
// inlined into AVX2 code only (see place_chunk_avx2).
template <class V, class I>
inline __attribute__((always_inline)) void place_math(const PlacementOf<V>& p, const V& x, const V& y, const V& z,
                                                      const V& r, const V& v, const V& t, PlacedVector<V, I>& out)
{
    const V f = (t - p.t_min_s) * p.inv_span_per_s;
    for (int row = 0; row < 3; ++row) {
        const V* a = p.at_start + 4 * row;
        const V* d = p.change + 4 * row;
        out.l[row] = (a[0] + f * d[0]) * x + (a[1] + f * d[1]) * y + (a[2] + f * d[2]) * z + (a[3] + f * d[3]);
    }
    const V raw = v + 2.0f * r * r * (p.error_at_start_rad2 + f * p.error_change_rad2);  // eq. 19-20
    // A NaN or infinity in any input leaves one in the position or the variance (x * 0 is
    // NaN for an infinite x, and inf - inf is NaN): checking the results checks the inputs.
    // x and y are checked by `inside` (false for NaN); the rare path finds out which reason.
    const I valid = ((out.l[2] * 0.0f + raw * 0.0f) == 0.0f) & (v >= 0.0f);
    out.variance_m2 = raw > p.min_variance_m2 ? raw : p.min_variance_m2;  // maxps: the minimum where raw is NaN
    out.weight = p.inverse_scale / out.variance_m2 + p.unit_weight;
    // Eq. 5-7: the cell (unwrapped i, j), clamped so that the conversion is defined for any
    // value (a < b ? a : b compiles to minps, a > b ? a : b to maxps).
    const V zero = V{};
    const V fx = out.l[0] * p.inv_g;
    const V fy = (out.l[1] - p.y_min_m) * p.inv_g;
    const I inside = (fx >= 0.0f) & (fx < p.nx) & (fy >= 0.0f) & (fy < p.ny);
    V i = fx > zero ? fx : zero;
    i = __builtin_convertvector(__builtin_convertvector(i < p.nx_last ? i : p.nx_last, I), V);
    V j = fy > zero ? fy : zero;
    j = __builtin_convertvector(__builtin_convertvector(j < p.ny_last ? j : p.ny_last, I), V);
    out.x_rel = out.l[0] - (i + 0.5f) * p.g;
    out.y_rel = out.l[1] - p.y_min_m - (j + 0.5f) * p.g;
    // Eq. 6 and its like for columns: physical = ((i + shift) mod rows) * stride + ((j +
    // shift) mod columns), in float (exact below 2^24 cells; a grid has at most 2^22).
    V row = i + p.row_shift;
    row = row >= p.ring_rows ? row - p.ring_rows : row;
    V column = j + p.column_shift;
    column = column >= p.ring_columns ? column - p.ring_columns : column;
    out.cell = __builtin_convertvector(row * p.row_stride + column, I);
    out.fuse = valid & inside & (out.variance_m2 <= p.spread_above_m2);
}

// The per-point results of place_math into out's arrays from point first on, one lane a
// point (V 4 or 8 floats wide; inlined, so the 8-wide copies are AVX2 code).
template <class V, class I>
inline __attribute__((always_inline)) void store_placed(const PlacedVector<V, I>& placed, PlacedPoints& out,
                                                         std::size_t first)
{
    std::memcpy(out.lx + first, &placed.l[0], sizeof(V));
    std::memcpy(out.ly + first, &placed.l[1], sizeof(V));
    std::memcpy(out.lz + first, &placed.l[2], sizeof(V));
    std::memcpy(out.variance_m2 + first, &placed.variance_m2, sizeof(V));
    std::memcpy(out.weight + first, &placed.weight, sizeof(V));
    std::memcpy(out.cell + first, &placed.cell, sizeof(I));
    std::memcpy(out.fuse + first, &placed.fuse, sizeof(I));
}

// Points first .. first+3 of a chunk (lanes beyond its count are padding) into out.
inline void place_points(const Placement& p, Float4 x, Float4 y, Float4 z, Float4 r, Float4 v, Float4 t,
                         PlacedPoints& out, std::size_t first)
{
    PlacedVector<Float4, Int4> placed;
    place_math(p, x, y, z, r, v, t, placed);
    store_placed(placed, out, first);
    out.all_fuse[first / 4] = lane_bits(placed.fuse) == 0xfu;
    // Transposed to one {0, x_rel, y_rel, z} per point.
    Float4 s0 = Float4{}, s1 = placed.x_rel, s2 = placed.y_rel, s3 = placed.l[2];
    transpose4(s0, s1, s2, s3);
    store4(out.sample[first + 0], s0);
    store4(out.sample[first + 1], s1);
    store4(out.sample[first + 2], s2);
    store4(out.sample[first + 3], s3);
}

// Points 0 .. count-1 of the six input arrays in[] (x, y, z, range, variance, time
// offset; count <= PlacedPoints::kCapacity) into out: place_points four at a time, or
// eight at a time with AVX2 (fusion_place.cpp).
using PlaceChunk = void (*)(const Placement& p, const float* const* in, std::size_t count, PlacedPoints& out);
void place_chunk_generic(const Placement& p, const float* const* in, std::size_t count, PlacedPoints& out);
#if defined(UGV_TERRAIN_HAVE_AVX2)
void place_chunk_avx2(const Placement& p, const float* const* in, std::size_t count, PlacedPoints& out);
#endif

}  // namespace ugv::terrain::detail
