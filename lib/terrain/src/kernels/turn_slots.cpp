#include "turn_slots.hpp"

#include <cstddef>
#include <cstring>

#include "float4.hpp"
#include "float8.hpp"

namespace ugv::terrain::detail {

// Both builds take a group of slots' sums across the lanes by a transpose (a cell is one row
// of the matrix, its sums {w, x_wx, y_wy, z_wz, z_ref_m, x_wx2, y_wy2, z_wz2} the columns;
// the AVX2 build forms only the columns the arithmetic uses), do the arithmetic of
// turn_sums on whole vectors, transpose back and store each cell where it was. An empty
// slot (w and z_ref_m NaN) computes NaN, which no comparison lets into the map; the
// arithmetic has no branch.

namespace {

static_assert(sizeof(CellSums) == 32 && offsetof(CellSums, z_ref_m) == 16);

// Empties and lists the slots first + k of the lanes k set in lost (known, but turned out
// of the map). After the turned cells' stores.
inline void drop(CellSums* sums, TurnTarget& out, uint32_t first, unsigned lost)
{
    for (; lost != 0; lost &= lost - 1) {
        const uint32_t s = first + static_cast<uint32_t>(__builtin_ctz(lost));
        sums[s] = CellSums{};
        out.dropped[out.drops++] = s;
    }
}

// The rotation's constants broadcast to vectors of type V.
template <class V>
struct TurnVectors
{
    V c, s, c_g, s_g, cc, ss, g, minus_half_g, nx, ny, inv_ny, ring_rows, row_shift_cells, column_shift, offset_x,
        offset_y;
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

// Eq. 9-16 on a vector of slots. home holds each slot's cell (physical index, as float),
// r[0..7] its sums {w, x_wx, y_wy, z_wz, z_ref_m, x_wx2, y_wy2, z_wz2}, one slot a lane (only
// w, x_wx, y_wy, x_wx2 and y_wy2 are read); x_wx, y_wy, x_wx2 and y_wy2 are replaced by their
// values about the new cell's centre. Sets cell (the working cell, ring-indexed; any value
// where the slot is not placed), the lanes placed (known, and landing in the map) and the
// lanes known. Everything by reference: with V 8 floats wide this is inlined into AVX2 code
// only.
template <class V, class I>
inline __attribute__((always_inline)) void turn_sums(const TurnVectors<V>& k, const V& home, V* r, int32_t cells,
                                                     I& cell, unsigned& placed, unsigned& known)
{
    const V w = r[0], x_wx = r[1], y_wy = r[2], x_wx2 = r[5], y_wy2 = r[6];
    const V zero = V{};
    // A known cell's w is above 0; an empty slot's is NaN, and so is everything that
    // follows from it, which keeps it out of the map. The division is the longest step:
    // what needs no quotient is done beside it, and each chain after it is short (an FMA to
    // the new row and column, an FMA to the variances).
    const V inv_w = 1.0f / w;
    // The cell's row and column from its physical index (exact: the grid has fewer than
    // 2^22 cells, see EgocentricGrid), both unwrapped (eq. 6). The turned cells are written
    // with no column shift.
    V physical_row, i_old;
    whole_below((home + 0.5f) * k.inv_ny, physical_row);
    V j_old = home - physical_row * k.ny - k.column_shift;
    j_old = j_old < zero ? j_old + k.ny : j_old;
    i_old = physical_row - k.ring_rows;
    i_old = i_old < zero ? i_old + k.nx : i_old;
    // Eq. 9-18: the centre plus the remainder (x_re, y_re) = (x_wx, y_wy) / w, turned with the
    // frame, in cells (eq. 15-16, 5-7).
    const V turned_x = k.c_g * x_wx + k.s_g * y_wy;
    const V turned_y = k.c_g * y_wy - k.s_g * x_wx;
    const V fx = turned_x * inv_w + (k.c * i_old + (k.s * j_old + k.offset_x));
    const V fy = turned_y * inv_w + (k.c * j_old - (k.s * i_old - k.offset_y));
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

// Slots first .. first + 3. Returns the lanes placed.
inline __attribute__((always_inline)) unsigned turn4(const TurnVectors<Float4>& k, CellSums* sums, uint32_t* home,
                                                     uint32_t first, int32_t cells, TurnTarget& out)
{
    CellSums* const src = sums + first;
    Float4 r[8] = {load4(&src[0].w),       load4(&src[1].w),       load4(&src[2].w),       load4(&src[3].w),
                   load4(&src[0].z_ref_m), load4(&src[1].z_ref_m), load4(&src[2].z_ref_m), load4(&src[3].z_ref_m)};
    transpose4(r[0], r[1], r[2], r[3]);
    transpose4(r[4], r[5], r[6], r[7]);
    Int4 cell;
    unsigned placed, known;
    const Float4 at = __builtin_convertvector(load4(reinterpret_cast<const int32_t*>(home + first)), Float4);
    turn_sums(k, at, r, cells, cell, placed, known);
    transpose4(r[0], r[1], r[2], r[3]);  // back to one cell per pair of vectors: r[c], r[c + 4]
    transpose4(r[4], r[5], r[6], r[7]);
    for (int c = 0; c < 4; ++c) {
        store4(&src[c].w, r[c]);
        store4(&src[c].z_ref_m, r[c + 4]);
    }
    std::memcpy(home + first, &cell, sizeof cell);
    for (int c = 0; c < 4; ++c)
        if (placed >> c & 1u) out.slot[cell[c]] = first + static_cast<uint32_t>(c);
    if (known != placed) [[unlikely]]
        drop(sums, out, first, known & ~placed);
    return placed;
}

}  // namespace

void turn_slots_generic(const TurnConstants& t, CellSums* sums, uint32_t* home, uint32_t slots, TurnTarget& target)
{
    const TurnVectors<Float4> k{splat(t.c),  splat(t.s),     splat(t.c_g),          splat(t.s_g),      splat(t.cc),
                                splat(t.ss), splat(t.g),     splat(t.minus_half_g), splat(t.nx),       splat(t.ny),
                                splat(t.inv_ny), splat(t.ring_rows), splat(t.row_shift_cells), splat(t.column_shift),
                                splat(t.offset_x),
                                splat(t.offset_y)};
    for (uint32_t first = 0; first < slots; first += 8) {
        const unsigned low = turn4(k, sums, home, first, t.cells, target);
        target.placed[first / 8] = static_cast<uint8_t>(low | turn4(k, sums, home, first + 4, t.cells, target) << 4);
    }
}

int find_merges_generic(const uint32_t* working_slot, const uint32_t* home, const uint8_t* placed, uint32_t slots,
                        uint32_t* merge_from, uint32_t* merge_into)
{
    int merges = 0;
    for (uint32_t first = 0; first < slots; first += 8) {
        for (unsigned bits = placed[first / 8]; bits != 0; bits &= bits - 1) {
            const uint32_t s = first + static_cast<uint32_t>(__builtin_ctz(bits));
            const uint32_t there = working_slot[home[s]];
            if (there == s) continue;
            merge_from[merges] = s;
            merge_into[merges++] = there;
        }
    }
    return merges;
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

// Slots first .. first + 7: one cell is one vector, loaded and stored where it is. Returns
// the lanes placed.
UGV_AVX2 inline __attribute__((always_inline)) unsigned turn8(const TurnVectors<Float8>& k, CellSums* sums, uint32_t* home,
                                                      uint32_t first, int32_t cells, TurnTarget& out)
{
    CellSums* const src = sums + first;
    const Float8 o[8] = {load8(&src[0].w), load8(&src[1].w), load8(&src[2].w), load8(&src[3].w),
                         load8(&src[4].w), load8(&src[5].w), load8(&src[6].w), load8(&src[7].w)};
    Float8 r[8], keep[4];
    transpose_in(o, r, keep);
    Int8 cell;
    unsigned placed, known;
    const Float8 at = Float8(_mm256_cvtepi32_ps(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(home + first))));
    turn_sums(k, at, r, cells, cell, placed, known);
    transpose_out(r, keep, r);
    for (int c = 0; c < 8; ++c) _mm256_store_ps(&src[c].w, __m256(r[c]));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(home + first), __m256i(cell));
    // No test whether the working cell is taken: a load there would wait for the stores
    // before it (find_merges finds the cells that landed together afterwards).
    uint32_t* const working_slot = out.slot;  // a local: stores through the target's pointers could alias its fields
    if (placed == 0xffu) {  // most groups: no test per cell
        for (int c = 0; c < 8; ++c) working_slot[static_cast<uint32_t>(cell[c])] = first + static_cast<uint32_t>(c);
        return placed;
    }
    for (int c = 0; c < 8; ++c)
        if (placed >> c & 1u) working_slot[static_cast<uint32_t>(cell[c])] = first + static_cast<uint32_t>(c);
    if (known != placed) drop(sums, out, first, known & ~placed);
    return placed;
}

}  // namespace

UGV_AVX2 void turn_slots_avx2(const TurnConstants& t, CellSums* sums, uint32_t* home, uint32_t slots,
                              TurnTarget& target)
{
    const TurnVectors<Float8> k{splat8(t.c),  splat8(t.s),     splat8(t.c_g),          splat8(t.s_g),      splat8(t.cc),
                                splat8(t.ss), splat8(t.g),     splat8(t.minus_half_g), splat8(t.nx),       splat8(t.ny),
                                splat8(t.inv_ny), splat8(t.ring_rows), splat8(t.row_shift_cells), splat8(t.column_shift),
                                splat8(t.offset_x),
                                splat8(t.offset_y)};
    for (uint32_t first = 0; first < slots; first += 8)
        target.placed[first / 8] = static_cast<uint8_t>(turn8(k, sums, home, first, t.cells, target));
}

UGV_AVX2 int find_merges_avx2(const uint32_t* working_slot, const uint32_t* home, const uint8_t* placed, uint32_t slots,
                              uint32_t* merge_from, uint32_t* merge_into)
{
    int merges = 0;
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    const __m256i bit = _mm256_setr_epi32(1, 2, 4, 8, 16, 32, 64, 128);
    for (uint32_t first = 0; first < slots; first += 8) {
        const unsigned bits = placed[first / 8];
        if (bits == 0) continue;
        // The working slots of the placed lanes' cells (the others are not read: their home
        // is any value).
        const __m256i mask = _mm256_cmpeq_epi32(_mm256_and_si256(_mm256_set1_epi32(static_cast<int>(bits)), bit), bit);
        const __m256i at = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(home + first));
        const __m256i there = _mm256_mask_i32gather_epi32(_mm256_setzero_si256(), reinterpret_cast<const int*>(working_slot),
                                                          at, mask, 4);
        const __m256i self = _mm256_add_epi32(_mm256_set1_epi32(static_cast<int>(first)), lane);
        unsigned other = bits & ~static_cast<unsigned>(_mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(there, self))));
        for (; other != 0; other &= other - 1) {
            const uint32_t s = first + static_cast<uint32_t>(__builtin_ctz(other));
            merge_from[merges] = s;
            merge_into[merges++] = working_slot[home[s]];
        }
    }
    return merges;
}

#endif

}  // namespace ugv::terrain::detail
