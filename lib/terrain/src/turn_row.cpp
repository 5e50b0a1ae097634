#include "turn_row.hpp"

#include <algorithm>
#include <cstddef>
#include <cstring>

#include "float4.hpp"
#include "float8.hpp"
#include "ugv/terrain/simd.hpp"

namespace ugv::terrain::detail {

// Both builds take the cells' sums across the lanes by a transpose (a cell is one row of
// the matrix, its sums {w, x_wx, y_wy, z_wz, z_ref_m, x_wx2, y_wy2, z_wz2} the columns), do
// the arithmetic of turn_sums on whole vectors, transpose back and store each cell where
// it lands. An empty cell (z_ref_m NaN) computes garbage that is never stored; the
// arithmetic has no branch.

namespace {

static_assert(sizeof(CellSums) == 32 && offsetof(CellSums, z_ref_m) == 16);

// Unknown ground is most of a real map (the demo's holds 37 % known cells): groups of
// empty cells skip the arithmetic.
bool all_empty(const CellSums* cells, int n)
{
    for (int k = 0; k < n; ++k)
        if (!cells[k].empty()) return false;
    return true;
}

// Where a turned cell's sums go: its working cell dst, taken with its count, or (rarely,
// the cell is taken) the merge list.
inline CellSums* place(CellSums* sums, uint32_t* counts, TurnTarget& out, int32_t dst, uint32_t count)
{
    uint32_t& taken = counts[dst];
    if (__builtin_expect(taken == 0, 1)) {
        taken = std::max(count, 1u);  // 0 only if 2^32 samples wrapped it
        return sums + dst;
    }
    const int m = out.merges++;
    out.merge_to[m] = dst;
    out.merge_counts[m] = count;
    return out.merge_sums + m;
}

// The rotation's constants broadcast to vectors of type V.
template <class V>
struct TurnVectors
{
    V c, s, cc, ss, inv_g, g, y_min, nx, ny, nx_last, ny_last, row_shift, row_stride, row_x;
};

// Eq. 9-16 on a vector of cells. r[0..7] hold the sums {w, x_wx, y_wy, z_wz, z_ref_m, x_wx2,
// y_wy2, z_wz2}, one cell a lane; x_wx, y_wy, x_wx2 and y_wy2 are replaced by their values
// about the new cell's centre. Sets cell (the working cell, unwrapped and ring-indexed),
// inside (the cell lands in the map) and known (it is not empty). Everything by reference
// and no helper calls: with V 8 floats wide this is inlined into AVX2 code only.
template <class V, class I>
inline __attribute__((always_inline)) void turn_sums(const TurnVectors<V>& k, V* r, const V& centre_y, I& cell,
                                                     I& inside, I& known)
{
    const V w = r[0], x_wx = r[1], y_wy = r[2], z_ref = r[4], x_wx2 = r[5], y_wy2 = r[6];
    const V zero = V{};
    const V inv_w = w > zero ? 1.0f / w : zero;  // an empty cell's w is NaN
    const V x_re = x_wx * inv_w;                 // eq. 9-10: the remainder
    const V y_re = y_wy * inv_w;
    const V x = k.row_x + x_re;  // eq. 17-18: the centre, plus the remainder
    const V y = centre_y + y_re;
    const V xn = k.c * x + k.s * y;  // eq. 11-14: the world stays, the frame turns
    const V yn = k.c * y - k.s * x;
    const V fx = xn * k.inv_g;  // eq. 15-16, 5-7
    const V fy = (yn - k.y_min) * k.inv_g;
    inside = (fx >= 0.0f) & (fx < k.nx) & (fy >= 0.0f) & (fy < k.ny);
    // Clamped so that the conversion is defined for any value (a < b ? a : b: minps).
    V i = fx > zero ? fx : zero;
    i = __builtin_convertvector(__builtin_convertvector(i < k.nx_last ? i : k.nx_last, I), V);
    V j = fy > zero ? fy : zero;
    j = __builtin_convertvector(__builtin_convertvector(j < k.ny_last ? j : k.ny_last, I), V);
    const V x_rel = xn - (i + 0.5f) * k.g;
    const V y_rel = yn - k.y_min - (j + 0.5f) * k.g;
    V row = i + k.row_shift;
    row = row >= k.nx ? row - k.nx : row;
    cell = __builtin_convertvector(row * k.row_stride + j, I);
    known = z_ref == z_ref;  // a NaN reference: an empty cell
    // The samples' spread about their mean, turned with the frame (the x-y covariance is
    // not kept, so the two variances mix by cos^2 and sin^2).
    V var_x = x_wx2 * inv_w - x_re * x_re;
    var_x = var_x > zero ? var_x : zero;
    V var_y = y_wy2 * inv_w - y_re * y_re;
    var_y = var_y > zero ? var_y : zero;
    r[1] = w * x_rel;
    r[2] = w * y_rel;
    r[5] = w * (k.cc * var_x + k.ss * var_y + x_rel * x_rel);
    r[6] = w * (k.ss * var_x + k.cc * var_y + y_rel * y_rel);
}

// The number of bits set in a 4-bit mask (baseline x86-64 has no popcnt instruction).
constexpr int kBitsSet[16] = {0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4};

// Cells src[0..3] (counts[0..3]; padding lanes are empty cells, never placed).
inline __attribute__((always_inline)) void turn4(const TurnVectors<Float4>& k, const CellSums* src,
                                                 const uint32_t* counts, const Float4& centre_y,
                                                 TurnTarget& out)
{
    Float4 r[8] = {load4(&src[0].w),       load4(&src[1].w),       load4(&src[2].w),       load4(&src[3].w),
                   load4(&src[0].z_ref_m), load4(&src[1].z_ref_m), load4(&src[2].z_ref_m), load4(&src[3].z_ref_m)};
    transpose4(r[0], r[1], r[2], r[3]);
    transpose4(r[4], r[5], r[6], r[7]);
    Int4 cell, inside, known;
    turn_sums(k, r, centre_y, cell, inside, known);
    transpose4(r[0], r[1], r[2], r[3]);  // back to one cell per pair of vectors: r[c], r[c + 4]
    transpose4(r[4], r[5], r[6], r[7]);
    out.turned_out += kBitsSet[lane_bits(known & ~inside)];
    const unsigned placed = lane_bits(known & inside);
    CellSums* const sums = out.sums;  // locals: stores through the target's pointers could alias its fields
    uint32_t* const taken = out.counts;
    for (int c = 0; c < 4; ++c) {
        if ((placed >> c & 1u) == 0) continue;
        CellSums* to = place(sums, taken, out, cell[c], counts[c]);
        store4(&to->w, r[c]);
        store4(&to->z_ref_m, r[c + 4]);
    }
}

}  // namespace

void turn_row_generic(const TurnConstants& t, const CellSums* cells, const uint32_t* counts, int ny, float row_x,
                      const float* centre_y, TurnTarget& target)
{
    const TurnVectors<Float4> k{splat(t.c),       splat(t.s),         splat(t.cc),         splat(t.ss),
                                splat(t.inv_g),   splat(t.g),         splat(t.y_min),      splat(t.nx),
                                splat(t.ny),      splat(t.nx_last),   splat(t.ny_last),    splat(t.row_shift),
                                splat(t.row_stride), splat(row_x)};
    int j = 0;
    for (; j + 4 <= ny; j += 4)
        if (!all_empty(cells + j, 4)) turn4(k, cells + j, counts + j, load4(centre_y + j), target);
    if (j < ny) {
        CellSums tail[4];  // the last 1-3 cells, padded with empty ones (never placed)
        std::copy(cells + j, cells + ny, tail);
        turn4(k, tail, counts + j, load4(centre_y + j), target);
    }
}

#if defined(UGV_TERRAIN_HAVE_AVX2)

namespace {

// The 8x8 transpose, in place: unpack pairs, then quads within each 128-bit half, then the
// halves.
UGV_AVX2 inline void transpose8(Float8* r)
{
    const Float8 t0 = __builtin_shufflevector(r[0], r[1], 0, 8, 1, 9, 4, 12, 5, 13);
    const Float8 t1 = __builtin_shufflevector(r[0], r[1], 2, 10, 3, 11, 6, 14, 7, 15);
    const Float8 t2 = __builtin_shufflevector(r[2], r[3], 0, 8, 1, 9, 4, 12, 5, 13);
    const Float8 t3 = __builtin_shufflevector(r[2], r[3], 2, 10, 3, 11, 6, 14, 7, 15);
    const Float8 t4 = __builtin_shufflevector(r[4], r[5], 0, 8, 1, 9, 4, 12, 5, 13);
    const Float8 t5 = __builtin_shufflevector(r[4], r[5], 2, 10, 3, 11, 6, 14, 7, 15);
    const Float8 t6 = __builtin_shufflevector(r[6], r[7], 0, 8, 1, 9, 4, 12, 5, 13);
    const Float8 t7 = __builtin_shufflevector(r[6], r[7], 2, 10, 3, 11, 6, 14, 7, 15);
    const Float8 s0 = __builtin_shufflevector(t0, t2, 0, 1, 8, 9, 4, 5, 12, 13);
    const Float8 s1 = __builtin_shufflevector(t0, t2, 2, 3, 10, 11, 6, 7, 14, 15);
    const Float8 s2 = __builtin_shufflevector(t1, t3, 0, 1, 8, 9, 4, 5, 12, 13);
    const Float8 s3 = __builtin_shufflevector(t1, t3, 2, 3, 10, 11, 6, 7, 14, 15);
    const Float8 s4 = __builtin_shufflevector(t4, t6, 0, 1, 8, 9, 4, 5, 12, 13);
    const Float8 s5 = __builtin_shufflevector(t4, t6, 2, 3, 10, 11, 6, 7, 14, 15);
    const Float8 s6 = __builtin_shufflevector(t5, t7, 0, 1, 8, 9, 4, 5, 12, 13);
    const Float8 s7 = __builtin_shufflevector(t5, t7, 2, 3, 10, 11, 6, 7, 14, 15);
    r[0] = __builtin_shufflevector(s0, s4, 0, 1, 2, 3, 8, 9, 10, 11);
    r[1] = __builtin_shufflevector(s1, s5, 0, 1, 2, 3, 8, 9, 10, 11);
    r[2] = __builtin_shufflevector(s2, s6, 0, 1, 2, 3, 8, 9, 10, 11);
    r[3] = __builtin_shufflevector(s3, s7, 0, 1, 2, 3, 8, 9, 10, 11);
    r[4] = __builtin_shufflevector(s0, s4, 4, 5, 6, 7, 12, 13, 14, 15);
    r[5] = __builtin_shufflevector(s1, s5, 4, 5, 6, 7, 12, 13, 14, 15);
    r[6] = __builtin_shufflevector(s2, s6, 4, 5, 6, 7, 12, 13, 14, 15);
    r[7] = __builtin_shufflevector(s3, s7, 4, 5, 6, 7, 12, 13, 14, 15);
}

// Cells src[0..7] (counts[0..7]; padding lanes are empty cells, never placed): one cell is one
// vector, stored with one 32-byte store.
UGV_AVX2 inline void turn8(const TurnVectors<Float8>& k, const CellSums* src, const uint32_t* counts,
                           const Float8& centre_y, TurnTarget& out)
{
    Float8 r[8] = {load8(&src[0].w), load8(&src[1].w), load8(&src[2].w), load8(&src[3].w),
                   load8(&src[4].w), load8(&src[5].w), load8(&src[6].w), load8(&src[7].w)};
    transpose8(r);
    Int8 cell, inside, known;
    turn_sums(k, r, centre_y, cell, inside, known);
    transpose8(r);
    out.turned_out += __builtin_popcount(lane_bits8(known & ~inside));
    const unsigned placed = lane_bits8(known & inside);
    CellSums* const sums = out.sums;  // locals: stores through the target's pointers could alias its fields
    uint32_t* const taken = out.counts;
    if (placed == 0xffu) {  // most groups of a known map: no test per cell
        for (int c = 0; c < 8; ++c) _mm256_storeu_ps(&place(sums, taken, out, cell[c], counts[c])->w, __m256(r[c]));
        return;
    }
    for (int c = 0; c < 8; ++c)
        if (placed >> c & 1u) _mm256_storeu_ps(&place(sums, taken, out, cell[c], counts[c])->w, __m256(r[c]));
}

}  // namespace

UGV_AVX2 void turn_row_avx2(const TurnConstants& t, const CellSums* cells, const uint32_t* counts, int ny, float row_x,
                            const float* centre_y, TurnTarget& target)
{
    const TurnVectors<Float8> k{splat8(t.c),       splat8(t.s),         splat8(t.cc),         splat8(t.ss),
                                splat8(t.inv_g),   splat8(t.g),         splat8(t.y_min),      splat8(t.nx),
                                splat8(t.ny),      splat8(t.nx_last),   splat8(t.ny_last),    splat8(t.row_shift),
                                splat8(t.row_stride), splat8(row_x)};
    int j = 0;
    for (; j + 8 <= ny; j += 8)
        if (!all_empty(cells + j, 8)) turn8(k, cells + j, counts + j, load8(centre_y + j), target);
    if (j < ny) {
        CellSums tail[8];  // the last 1-7 cells, padded with empty ones (never placed)
        std::copy(cells + j, cells + ny, tail);
        turn8(k, tail, counts + j, load8(centre_y + j), target);
    }
}

#endif

TurnRow turn_row_kernel()
{
#if defined(UGV_TERRAIN_HAVE_AVX2)
    if (simd_level() == SimdLevel::avx2) return turn_row_avx2;
#endif
    return turn_row_generic;
}

}  // namespace ugv::terrain::detail
