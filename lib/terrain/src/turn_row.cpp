#include "turn_row.hpp"

#include <algorithm>
#include <cstddef>
#include <cstring>

#include "float4.hpp"
#include "float8.hpp"
#include "ugv/terrain/simd.hpp"

namespace ugv::terrain::detail {

// Both builds take the cells' sums across the lanes by a transpose (a cell is one row of
// the matrix, its sums {w, x_wx, y_wy, z_wz, z_ref_m, x_wx2, y_wy2, z_wz2} the columns; the
// AVX2 build forms only the columns the arithmetic uses), do the arithmetic of turn_sums on
// whole vectors, transpose back and store each cell where it lands. An empty cell (w and
// z_ref_m NaN) computes NaN, which no comparison lets into the map; the arithmetic has no
// branch.

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
// the cell is taken) the merge list. The count is at least 1 (the cell's own is 0 only if
// 2^32 samples wrapped it): a count is how the next cell sees that its working cell is taken.
inline __attribute__((always_inline)) CellSums* place(CellSums* sums, uint32_t* counts, TurnTarget& out, int32_t dst,
                                                      uint32_t count)
{
    uint32_t& taken = counts[dst];
    if (__builtin_expect(taken == 0, 1)) {
        taken = count;
        return sums + dst;
    }
    const int m = out.merges++;
    out.merge_to[m] = dst;
    out.merge_counts[m] = count;
    return out.merge_sums + m;
}

// The rotation's constants broadcast to vectors of type V, and the row's.
template <class V>
struct TurnVectors
{
    V c_g, s_g, cc, ss, g, minus_half_g, nx, ny, row_shift_cells, row_x, row_y;
};

// The two steps of turn_sums that each build does its own way, with results by reference
// (an 8-float vector returned by value would not be AVX code in the template):
// - whole_below: the whole numbers below v, for v >= 0 (any value for v < 0 or not a number:
//   such a cell is outside the map, and never placed);
// - ring_cell: the working cell of row i, column j, (i + m_i) mod nx rows on (eq. 6), for a
//   cell inside.
inline void whole_below(const Float4& v, Float4& whole) { whole = __builtin_convertvector(truncate_to_int(v), Float4); }
inline void ring_cell(const TurnVectors<Float4>& k, const Float4& i, const Float4& j, int32_t cells, Int4& cell)
{
    const Int4 c = truncate_to_int(i * k.ny + (j + k.row_shift_cells));  // a row is ny cells
    cell = c - ((c > cells - 1) & cells);  // comparison lanes are 0 or -1
}
#if defined(UGV_TERRAIN_HAVE_AVX2)
UGV_AVX2 inline void whole_below(const Float8& v, Float8& whole) { whole = Float8(_mm256_floor_ps(__m256(v))); }
UGV_AVX2 inline void ring_cell(const TurnVectors<Float8>& k, const Float8& i, const Float8& j, int32_t cells, Int8& cell)
{
    const __m256i c = _mm256_cvttps_epi32(__m256(i * k.ny + (j + k.row_shift_cells)));  // a row is ny cells
    cell = Int8(_mm256_min_epu32(c, _mm256_sub_epi32(c, _mm256_set1_epi32(cells))));  // c - cells: above c unless c >= cells
}
#endif

// Eq. 9-16 on a vector of cells. r[0..7] hold the sums {w, x_wx, y_wy, z_wz, z_ref_m, x_wx2,
// y_wy2, z_wz2}, one cell a lane (only w, x_wx, y_wy, x_wx2 and y_wy2 are read); x_wx, y_wy,
// x_wx2 and y_wy2 are replaced by their values about the new cell's centre. Sets cell (the
// working cell, ring-indexed; any value where the cell is not placed), the lanes placed
// (known, and landing in the map) and the lanes known. Everything by reference: with V 8
// floats wide this is inlined into AVX2 code only.
template <class V, class I>
inline __attribute__((always_inline)) void turn_sums(const TurnVectors<V>& k, V* r, const V& column_x,
                                                     const V& column_y, int32_t cells, I& cell, unsigned& placed,
                                                     unsigned& known)
{
    const V w = r[0], x_wx = r[1], y_wy = r[2], x_wx2 = r[5], y_wy2 = r[6];
    const V zero = V{};
    // A known cell's w is above 0; an empty cell's is NaN, and so is everything that
    // follows from it, which keeps it out of the map. The division is the longest step:
    // what needs no quotient is done beside it, and each chain after it is short (an FMA to
    // the new row and column, an FMA to the variances).
    const V inv_w = 1.0f / w;
    // Eq. 9-18: the centre plus the remainder (x_re, y_re) = (x_wx, y_wy) / w, turned with the
    // frame, in cells (eq. 15-16, 5-7).
    const V turned_x = k.c_g * x_wx + k.s_g * y_wy;
    const V turned_y = k.c_g * y_wy - k.s_g * x_wx;
    const V fx = turned_x * inv_w + (k.row_x + column_x);
    const V fy = turned_y * inv_w + (column_y - k.row_y);
    // The samples' spread about their mean, times w: w var = sum w x^2 - (sum w x)^2 / w.
    V w_var_x = x_wx2 - (x_wx * x_wx) * inv_w;
    w_var_x = w_var_x > zero ? w_var_x : zero;
    V w_var_y = y_wy2 - (y_wy * y_wy) * inv_w;
    w_var_y = w_var_y > zero ? w_var_y : zero;
    // Turned with the frame (the x-y covariance is not kept, so the two mix by cos^2 and sin^2).
    const V turned_var_x = k.cc * w_var_x + k.ss * w_var_y;
    const V turned_var_y = k.ss * w_var_x + k.cc * w_var_y;
    const V lower = fx < fy ? fx : fy;
    placed = lane_bits((lower >= 0.0f) & (fx < k.nx) & (fy < k.ny));
    known = lane_bits(w == w);
    V i, j;
    whole_below(fx, i);
    whole_below(fy, j);
    ring_cell(k, i, j, cells, cell);
    const V x_rel = (fx - i) * k.g + k.minus_half_g;  // from the new cell's centre (m)
    const V y_rel = (fy - j) * k.g + k.minus_half_g;
    r[1] = w * x_rel;
    r[2] = w * y_rel;
    r[5] = r[1] * x_rel + turned_var_x;
    r[6] = r[2] * y_rel + turned_var_y;
}

// The number of bits set in a 4-bit mask (baseline x86-64 has no popcnt instruction).
constexpr int kBitsSet[16] = {0, 1, 1, 2, 1, 2, 2, 3, 1, 2, 2, 3, 2, 3, 3, 4};

// Cells src[0..3] (counts[0..3]; padding lanes are empty cells, never placed). Returns the
// lanes that hold sums.
inline __attribute__((always_inline)) unsigned turn4(const TurnVectors<Float4>& k, const CellSums* src,
                                                 const uint32_t* counts, const float* column_x,
                                                 const float* column_y, int32_t cells, TurnTarget& out)
{
    Float4 r[8] = {load4(&src[0].w),       load4(&src[1].w),       load4(&src[2].w),       load4(&src[3].w),
                   load4(&src[0].z_ref_m), load4(&src[1].z_ref_m), load4(&src[2].z_ref_m), load4(&src[3].z_ref_m)};
    transpose4(r[0], r[1], r[2], r[3]);
    transpose4(r[4], r[5], r[6], r[7]);
    Int4 cell;
    unsigned placed, known;
    turn_sums(k, r, load4(column_x), load4(column_y), cells, cell, placed, known);
    transpose4(r[0], r[1], r[2], r[3]);  // back to one cell per pair of vectors: r[c], r[c + 4]
    transpose4(r[4], r[5], r[6], r[7]);
    out.turned_out += kBitsSet[known & ~placed];
    CellSums* const sums = out.sums;  // locals: stores through the target's pointers could alias its fields
    uint32_t* const taken = out.counts;
    for (int c = 0; c < 4; ++c) {
        if ((placed >> c & 1u) == 0) continue;
        CellSums* to = place(sums, taken, out, cell[c], std::max(counts[c], 1u));
        store4(&to->w, r[c]);
        store4(&to->z_ref_m, r[c + 4]);
    }
    return known;
}

}  // namespace

void turn_row_generic(const TurnConstants& t, const CellSums* cells, uint32_t* counts, int ny, float row_x,
                      float row_y, const float* column_x, const float* column_y, TurnTarget& target)
{
    const TurnVectors<Float4> k{splat(t.c_g), splat(t.s_g), splat(t.cc),  splat(t.ss),
                                splat(t.g),   splat(t.minus_half_g), splat(t.nx), splat(t.ny),
                                splat(t.row_shift_cells), splat(row_x), splat(row_y)};
    std::memset(target.known_row, 0, static_cast<std::size_t>(ny + 7) / 8);
    int j = 0;
    for (; j + 4 <= ny; j += 4)
        if (!all_empty(cells + j, 4))
            target.known_row[j / 8] |= static_cast<uint8_t>(
                turn4(k, cells + j, counts + j, column_x + j, column_y + j, t.cells, target) << (j % 8));
    if (j < ny) {
        CellSums tail[4];  // the last 1-3 cells, padded with empty ones (never placed)
        std::copy(cells + j, cells + ny, tail);
        target.known_row[j / 8] |= static_cast<uint8_t>(
            turn4(k, tail, counts + j, column_x + j, column_y + j, t.cells, target) << (j % 8));
    }
    std::fill(counts, counts + ny, 0u);
}

#if defined(UGV_TERRAIN_HAVE_AVX2)

namespace {

// The AVX2 build's transposes form only what the arithmetic reads and writes: the 8x8
// transpose is three steps (unpack pairs, then quads within each 128-bit half, then across
// the halves), and its last step, the one across halves, is needed for five of the eight
// sums on the way in and four on the way back: 39 shuffles instead of 48 (side_by_side:
// 1.5-3 % less time for a full map in three runs; the transposes are about a third of the
// rotation, but fewer shuffles have bought little each time they were tried).
//
// Way in: o[0..7] are cells 0-7 as loaded. Sets r[0] = w, r[1] = x_wx, r[2] = y_wy,
// r[5] = x_wx2, r[6] = y_wy2 of the eight cells (r[3], r[4], r[7] are not formed) and keeps
// the second step's quads the way back needs: keep[0] = {w | z_ref_m} of cells 0-3,
// keep[1] = {z_wz | z_wz2} of cells 0-3, keep[2], keep[3] the same of cells 4-7.
UGV_AVX2 inline __attribute__((always_inline)) void transpose_in(const Float8* o, Float8* r, Float8* keep)
{
    Float8 t[8];  // pairs of cells 2p, 2p + 1 interleaved
    for (int p = 0; p < 4; ++p) {
        t[2 * p] = __builtin_shufflevector(o[2 * p], o[2 * p + 1], 0, 8, 1, 9, 4, 12, 5, 13);
        t[2 * p + 1] = __builtin_shufflevector(o[2 * p], o[2 * p + 1], 2, 10, 3, 11, 6, 14, 7, 15);
    }
    // Quads: {w | z_ref_m}, {x_wx | x_wx2}, {y_wy | y_wy2}, {z_wz | z_wz2} of cells 0-3 (a) and 4-7 (b).
    keep[0] = __builtin_shufflevector(t[0], t[2], 0, 1, 8, 9, 4, 5, 12, 13);
    const Float8 xa_a = __builtin_shufflevector(t[0], t[2], 2, 3, 10, 11, 6, 7, 14, 15);
    const Float8 yb_a = __builtin_shufflevector(t[1], t[3], 0, 1, 8, 9, 4, 5, 12, 13);
    keep[1] = __builtin_shufflevector(t[1], t[3], 2, 3, 10, 11, 6, 7, 14, 15);
    keep[2] = __builtin_shufflevector(t[4], t[6], 0, 1, 8, 9, 4, 5, 12, 13);
    const Float8 xa_b = __builtin_shufflevector(t[4], t[6], 2, 3, 10, 11, 6, 7, 14, 15);
    const Float8 yb_b = __builtin_shufflevector(t[5], t[7], 0, 1, 8, 9, 4, 5, 12, 13);
    keep[3] = __builtin_shufflevector(t[5], t[7], 2, 3, 10, 11, 6, 7, 14, 15);
    // Across the halves: cells 0-3 from a, 4-7 from b.
    r[0] = __builtin_shufflevector(keep[0], keep[2], 0, 1, 2, 3, 8, 9, 10, 11);
    r[1] = __builtin_shufflevector(xa_a, xa_b, 0, 1, 2, 3, 8, 9, 10, 11);
    r[5] = __builtin_shufflevector(xa_a, xa_b, 4, 5, 6, 7, 12, 13, 14, 15);
    r[2] = __builtin_shufflevector(yb_a, yb_b, 0, 1, 2, 3, 8, 9, 10, 11);
    r[6] = __builtin_shufflevector(yb_a, yb_b, 4, 5, 6, 7, 12, 13, 14, 15);
}

// Way back: the cells, one vector each, into o[0..7] (o may be r), from the new r[1], r[2],
// r[5], r[6] and the quads kept on the way in; the steps of transpose_in undone.
UGV_AVX2 inline __attribute__((always_inline)) void transpose_out(const Float8* r, const Float8* keep, Float8* o)
{
    const Float8 xa_a = __builtin_shufflevector(r[1], r[5], 0, 1, 2, 3, 8, 9, 10, 11);
    const Float8 xa_b = __builtin_shufflevector(r[1], r[5], 4, 5, 6, 7, 12, 13, 14, 15);
    const Float8 yb_a = __builtin_shufflevector(r[2], r[6], 0, 1, 2, 3, 8, 9, 10, 11);
    const Float8 yb_b = __builtin_shufflevector(r[2], r[6], 4, 5, 6, 7, 12, 13, 14, 15);
    const Float8 t[8] = {__builtin_shufflevector(keep[0], xa_a, 0, 1, 8, 9, 4, 5, 12, 13),
                         __builtin_shufflevector(yb_a, keep[1], 0, 1, 8, 9, 4, 5, 12, 13),
                         __builtin_shufflevector(keep[0], xa_a, 2, 3, 10, 11, 6, 7, 14, 15),
                         __builtin_shufflevector(yb_a, keep[1], 2, 3, 10, 11, 6, 7, 14, 15),
                         __builtin_shufflevector(keep[2], xa_b, 0, 1, 8, 9, 4, 5, 12, 13),
                         __builtin_shufflevector(yb_b, keep[3], 0, 1, 8, 9, 4, 5, 12, 13),
                         __builtin_shufflevector(keep[2], xa_b, 2, 3, 10, 11, 6, 7, 14, 15),
                         __builtin_shufflevector(yb_b, keep[3], 2, 3, 10, 11, 6, 7, 14, 15)};
    for (int p = 0; p < 4; ++p) {
        o[2 * p] = __builtin_shufflevector(t[2 * p], t[2 * p + 1], 0, 2, 8, 10, 4, 6, 12, 14);
        o[2 * p + 1] = __builtin_shufflevector(t[2 * p], t[2 * p + 1], 1, 3, 9, 11, 5, 7, 13, 15);
    }
}

// place for one 8-float cell, with the store in each branch: a store through place's
// returned pointer measured 4 % slower over the whole rotation (side_by_side/rotation.sh).
UGV_AVX2 inline __attribute__((always_inline)) void put8(CellSums* sums, uint32_t* taken, TurnTarget& out,
                                                         uint32_t dst, uint32_t n, const Float8& cell)
{
    if (__builtin_expect(taken[dst] == 0, 1)) {
        taken[dst] = n;
        _mm256_store_ps(&sums[dst].w, __m256(cell));
        return;
    }
    const int m = out.merges++;
    out.merge_to[m] = static_cast<int32_t>(dst);
    out.merge_counts[m] = n;
    _mm256_storeu_ps(&out.merge_sums[m].w, __m256(cell));
}

// Cells src[0..7] (counts[0..7]; padding lanes are empty cells, never placed): one cell is one
// vector, stored with one 32-byte store. Returns the lanes that hold sums.
UGV_AVX2 inline __attribute__((always_inline)) unsigned turn8(const TurnVectors<Float8>& k, const CellSums* src,
                                                          const uint32_t* counts, const float* column_x,
                                                          const float* column_y, int32_t cells, TurnTarget& out)
{
    const Float8 o[8] = {load8(&src[0].w), load8(&src[1].w), load8(&src[2].w), load8(&src[3].w),
                         load8(&src[4].w), load8(&src[5].w), load8(&src[6].w), load8(&src[7].w)};
    Float8 r[8], keep[4];
    transpose_in(o, r, keep);
    Int8 cell;
    unsigned placed, known;
    turn_sums(k, r, load8(column_x), load8(column_y), cells, cell, placed, known);
    transpose_out(r, keep, r);
    out.turned_out += __builtin_popcount(known & ~placed);
    // At least 1 (see place).
    const Int8 n = Int8(_mm256_max_epu32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(counts)),
                                         _mm256_set1_epi32(1)));
    CellSums* const sums = out.sums;  // locals: stores through the target's pointers could alias its fields
    uint32_t* const taken = out.counts;
    if (placed == 0xffu) {  // most groups of a known map: no test per cell
        for (int c = 0; c < 8; ++c) put8(sums, taken, out, static_cast<uint32_t>(cell[c]), static_cast<uint32_t>(n[c]), r[c]);
        return known;
    }
    for (int c = 0; c < 8; ++c)
        if (placed >> c & 1u) put8(sums, taken, out, static_cast<uint32_t>(cell[c]), static_cast<uint32_t>(n[c]), r[c]);
    return known;
}

}  // namespace

UGV_AVX2 void turn_row_avx2(const TurnConstants& t, const CellSums* cells, uint32_t* counts, int ny, float row_x,
                            float row_y, const float* column_x, const float* column_y, TurnTarget& target)
{
    const TurnVectors<Float8> k{splat8(t.c_g), splat8(t.s_g), splat8(t.cc),  splat8(t.ss),
                                splat8(t.g),   splat8(t.minus_half_g), splat8(t.nx), splat8(t.ny),
                                splat8(t.row_shift_cells), splat8(row_x), splat8(row_y)};
    int j = 0;
    for (; j + 8 <= ny; j += 8) {
        target.known_row[j / 8] = all_empty(cells + j, 8) ? 0
                                  : static_cast<uint8_t>(turn8(k, cells + j, counts + j, column_x + j, column_y + j,
                                                               t.cells, target));
        _mm256_storeu_si256(reinterpret_cast<__m256i*>(counts + j), _mm256_setzero_si256());
    }
    if (j < ny) {
        CellSums tail[8];  // the last 1-7 cells, padded with empty ones (never placed)
        std::copy(cells + j, cells + ny, tail);
        uint32_t tail_counts[8] = {};  // turn8 loads eight: none past the end of the map
        std::copy(counts + j, counts + ny, tail_counts);
        target.known_row[j / 8] =
            static_cast<uint8_t>(turn8(k, tail, tail_counts, column_x + j, column_y + j, t.cells, target));
        std::fill(counts + j, counts + ny, 0u);
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
