// Section 3.5 spreading at a cost that does not grow with the footprint (summed-area form).
// Private to the library.
//
// A spread point gives cell (a, b) the share w fx[a] fy[b] of its weight, fx and fy being
// the footprint's overlap with each row and column over its width (spread.hpp). Along one
// axis the overlap of [lo, hi] with cell k is S(k; lo) - S(k; hi), S(k; p) = clamp(k + 1 -
// p, 0, 1), whose first difference in k is non-zero in two cells only (floor(p): 1 - frac
// p; floor(p) + 1: frac p). So the whole footprint is the 2-D running sum of 4 x 4 corner
// entries, however wide it is; the centroid terms of the exact path (share times the
// offset of its part's centroid, and times its square) are non-zero only in the footprint's
// edge cells and take the same corners. A spread point adds one record at each of its 16
// corners here; flush() forms the running sums once and adds each touched cell's total to
// the map, as one sample set (add_sums). The running sums are formed only where a pending
// footprint lies, not over their bounding box (a nodding laser's arcs cross the whole map
// but cover a band of it): along a row, the prefix of a row's corners is zero outside the
// columns its footprints span (each footprint's corners in a row sum to zero); down a
// column, the running sum is zero once its count returns to 0 (counts are whole numbers,
// exact in double), and the column then leaves the active set. The result equals the
// exact path (TerrainMapper, spread_exact) up to rounding: the corners and running sums are
// in double, the fractions in float as the exact path takes them.
//
// The centred form (SpreadSumsOf<4>, spread_form = centred) keeps the first four components
// only: each share sits at the centre of its cell, not at the centroid of its part, so a
// cell's weight, mean, variance, count and extremes are the exact path's up to rounding and
// only the x/y sums of the footprint's edge cells differ (what a rotation bins by). Its
// corner record is one 4-double vector, half the stores and running sums of the full one.
//
// What is not a sum: a share's time. Every cell a pending share touches takes the newest
// time of the pending shares at the flush (the map flushes before it moves and before it is
// read, so the error is below one pose period while driving, one publish period standing).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <type_traits>
#include <vector>

#include "cell_fusion.hpp"
#include "kernels/kernel_table.hpp"
#include "ugv/terrain/cell_array.hpp"
#include "ugv/terrain/map_config.hpp"

namespace ugv::terrain::detail {

// GCC sizes a vector type only from a constant, not from a template argument.
using CornerRecord8 = double __attribute__((vector_size(8 * sizeof(double))));
using CornerRecord4 = double __attribute__((vector_size(4 * sizeof(double))));

// K: the components of a corner record, 8 (all the exact path's sums) or 4 (centred).
template <int K>
class SpreadSumsOf
{
public:
    // The components of a corner record (and of a cell's total after the running sums).
    static constexpr int kW = 0, kWz = 1, kWz2 = 2, kN = 3, kX1 = 4, kX2 = 5, kY1 = 6, kY2 = 7;
    static constexpr bool kCentred = K == kCentredCornerComponents;
    using Record = std::conditional_t<kCentred, CornerRecord4, CornerRecord8>;
    static_assert((K == kCornerComponents || kCentred) && sizeof(Record) == K * sizeof(double));

    SpreadSumsOf(int rows, int columns)
        : rows_(rows),
          columns_(columns),
          stride_(static_cast<std::size_t>(columns) + 2),
          words_((stride_ + 63) / 64),
          corner_storage_(((static_cast<std::size_t>(rows) + 3) * stride_ + 1) * K),
          extremes_(static_cast<std::size_t>(rows) * static_cast<std::size_t>(columns)),
          spans_((static_cast<std::size_t>(rows) + 2) * words_),
          active_(words_)
    {
        // Records aligned to their size (a vector of them would not be: operator new gives 16).
        void* p = corner_storage_.data();
        std::size_t space = corner_storage_.size() * sizeof(double);
        corners_ = static_cast<Record*>(std::align(sizeof(Record), sizeof(Record), p, space));
        running_ = corners_ + (static_cast<std::size_t>(rows) + 2) * stride_;
    }
    SpreadSumsOf(const SpreadSumsOf&) = delete;
    SpreadSumsOf& operator=(const SpreadSumsOf&) = delete;

    bool pending() const { return pending_; }

    // One spread point: centre (cx, cy) in cells from the grid's corner (unwrapped), half
    // width h cells, weight w, height z (ENU), time t_ms. Returns false when its footprint
    // misses the grid (nothing added).
    bool add(float cx, float cy, float h, float w, float g, float z, TimeTick t_ms)
    {
        Axis ax, ay;
        if (!axis(cx, h, rows_, g, ax) || !axis(cy, h, columns_, g, ay)) return false;
        if (!pending_) {
            pending_ = true;
            corners_kernel_ = kCentred ? kernels().spread_corners_centred : kernels().spread_corners;  // once per pending set, not per point
            z0_ = z;
            newest_ms_ = t_ms;
            row_lo_ = ax.at[0];
            row_hi_ = ax.at[3];
        } else {
            newest_ms_ = std::max(newest_ms_, t_ms);
            row_lo_ = std::min(row_lo_, ax.at[0]);
            row_hi_ = std::max(row_hi_, ax.at[3]);
        }
        mark_span(ax.at, ay.at[0], ay.at[3]);
        const double dz = static_cast<double>(z) - z0_;
        const double wd = static_cast<double>(w);
        const double wz = wd * dz, wz2 = wz * dz;
        // The corner record is rows[a] * columns[b], component by component (spread_corners.hpp).
        const double weight[3] = {wd, wz, wz2};
        corners_kernel_(reinterpret_cast<double*>(corners_), stride_, ax.at, ay.at, weight, ax, ay);
        // Its height goes into the extremes of the cell it was measured in only (section 3.5).
        // (Truncation is the floor for cx, cy >= 0; std::floor is a library call without SSE4.1.)
        if (cx >= 0.0f && cy >= 0.0f) {
            const int own_row = static_cast<int>(cx), own_column = static_cast<int>(cy);
            if (own_row < rows_ && own_column < columns_)
                extremes_[static_cast<std::size_t>(own_row) * static_cast<std::size_t>(columns_) +
                          static_cast<std::size_t>(own_column)]
                    .add(z);
        }
        return true;
    }

    // The running sums over the pending corners' box, each touched cell's total added to the
    // grid (unwrapped row i, column j is grid.physical(i, j)); afterwards nothing is pending.
    template <class Grid>
    void flush(Grid& grid)
    {
        if (!pending_) return;
        pending_ = false;
        const CellArrays cells(grid.cells());
        for (int i = row_lo_; i <= row_hi_; ++i) {
            Record* line = corners_ + static_cast<std::size_t>(i) * stride_;
            uint64_t* span = spans_.data() + static_cast<std::size_t>(i) * words_;
            // The prefix of the row's corners into the running sums, over the columns its
            // footprints span; across a gap between spans it is zero up to rounding.
            Record along{};
            int last = -2;
            for (std::size_t word = 0; word < words_; ++word) {
                active_[word] |= span[word];
                for (uint64_t bits = span[word]; bits != 0; bits &= bits - 1) {
                    const int j = static_cast<int>(word * 64) + __builtin_ctzll(bits);
                    if (j != last + 1) along = Record{};
                    last = j;
                    along += line[j];
                    line[j] = Record{};
                    running_[j] += along;
                }
                span[word] = 0;
            }
            // The running sums of the columns an open footprint covers: each touched cell's
            // total into the grid. A column whose count is back to 0 holds rounding only.
            for (std::size_t word = 0; word < words_; ++word) {
                for (uint64_t bits = active_[word]; bits != 0; bits &= bits - 1) {
                    const int j = static_cast<int>(word * 64) + __builtin_ctzll(bits);
                    Record& total = running_[j];
                    if (total[kN] > 0.5) {
                        if (i < rows_ && j < columns_) add_to(grid, cells, i, j, total);
                    } else {
                        total = Record{};
                        active_[word] &= ~(uint64_t{1} << (j & 63));
                    }
                }
            }
        }
        // Every footprint closes by its last corner row; what is left is rounding.
        for (std::size_t word = 0; word < words_; ++word) {
            for (uint64_t bits = active_[word]; bits != 0; bits &= bits - 1)
                running_[static_cast<int>(word * 64) + __builtin_ctzll(bits)] = Record{};
            active_[word] = 0;
        }
    }

    // The pending corners dropped (the map was cleared).
    void discard()
    {
        if (!pending_) return;
        for (int i = row_lo_; i <= row_hi_; ++i) {
            Record* line = corners_ + static_cast<std::size_t>(i) * stride_;
            uint64_t* span = spans_.data() + static_cast<std::size_t>(i) * words_;
            for (std::size_t word = 0; word < words_; ++word) {
                for (uint64_t bits = span[word]; bits != 0; bits &= bits - 1)
                    line[static_cast<int>(word * 64) + __builtin_ctzll(bits)] = Record{};
                span[word] = 0;
            }
        }
        std::fill(extremes_.begin(), extremes_.end(), CellExtremes{});
        pending_ = false;
    }

private:
    // One axis of a footprint: the four corner positions (cells, >= 0, <= limit + 1) and each
    // one's entries: the overlap fraction's difference, the touched count's, the centroid
    // moment's (share times centroid offset, m) and its square's (m^2).
    struct Axis : CornerAxis
    {
        int at[4];
    };

    // The footprint [c - h, c + h] clamped to [0, limit) and renormalised, as axis_footprint.
    static bool axis(float c, float h, int limit, float g, Axis& out)
    {
        h = std::clamp(h, 1e-6f, static_cast<float>(kMaxSpreadCells));
        const float lo = std::max(c - h, 0.0f);
        const float hi = std::min(c + h, static_cast<float>(limit));
        if (!(hi > lo)) return false;
        const double inv = 1.0 / static_cast<double>(hi - lo);
        const int lo0 = static_cast<int>(lo), hi0 = static_cast<int>(hi);  // floor: both >= 0
        const double ql = static_cast<double>(lo - static_cast<float>(lo0));
        const double qh = static_cast<double>(hi - static_cast<float>(hi0));
        out.at[0] = lo0;
        out.at[1] = lo0 + 1;
        out.at[2] = hi0;
        out.at[3] = hi0 + 1;
        out.fraction[0] = (1.0 - ql) * inv;
        out.fraction[1] = ql * inv;
        out.fraction[2] = -(1.0 - qh) * inv;
        out.fraction[3] = -qh * inv;
        // Touched: cells lo0 .. ceil(hi) - 1.
        out.count[0] = 1.0;
        out.count[1] = 0.0;
        out.count[2] = qh > 0.0 ? 0.0 : -1.0;
        out.count[3] = qh > 0.0 ? -1.0 : 0.0;
        if constexpr (kCentred) return true;
        // The integral of (x - cell centre) over the part of the edge cell from p on is
        // q (1 - q) / 2 (q = frac p); interior cells are whole, their integral 0.
        const double gd = static_cast<double>(g);
        const double ml = 0.5 * ql * (1.0 - ql) * inv * gd, mh = 0.5 * qh * (1.0 - qh) * inv * gd;
        out.moment[0] = ml;
        out.moment[1] = -ml;
        out.moment[2] = -mh;
        out.moment[3] = mh;
        // Fraction times the squared centroid offset, in the edge cells.
        double tl = 0.0, th = 0.0;
        if (lo0 == hi0) {
            const double centre = 0.5 * (ql + qh) - 0.5;
            tl = (qh - ql) * centre * centre;
        } else {
            tl = (1.0 - ql) * 0.25 * ql * ql;
            th = qh * 0.25 * (1.0 - qh) * (1.0 - qh);
        }
        tl *= inv * gd * gd;
        th *= inv * gd * gd;
        out.moment2[0] = tl;
        out.moment2[1] = -tl;
        out.moment2[2] = th;
        out.moment2[3] = -th;
        return true;
    }

    // Columns lo .. hi (inclusive; at most 2 kMaxSpreadCells + 2 of them, so in one word or
    // two) of the four corner rows are spanned by a pending footprint.
    void mark_span(const int* rows, int lo, int hi)
    {
        static_assert(2 * kMaxSpreadCells + 2 <= 64);
        const std::size_t first = static_cast<std::size_t>(lo >> 6), last = static_cast<std::size_t>(hi >> 6);
        const uint64_t from_lo = ~uint64_t{0} << (lo & 63), to_hi = ~uint64_t{0} >> (63 - (hi & 63));
        for (int a = 0; a < 4; ++a) {
            uint64_t* span = spans_.data() + static_cast<std::size_t>(rows[a]) * words_;
            if (first == last) {
                span[first] |= from_lo & to_hi;
            } else {
                span[first] |= from_lo;
                span[last] |= to_hi;
            }
        }
    }

    template <class Grid>
    void add_to(Grid& grid, const CellArrays& cells, int i, int j, const Record& total)
    {
        const uint32_t at = grid.storage_of(grid.physical(i, j));
        const double w = total[kW];
        CellSums& a = cells.sums[at];
        if (!(w <= a.w)) [[unlikely]] {
            // Empty, or the shares outweigh the cell: they become the cell, about their own
            // mean height, and the cell is added to them (the heavier side keeps its reference).
            const double mean = z0_ + total[kWz] / w;
            CellSums b;
            b.w = static_cast<float>(w);
            b.z_ref_m = static_cast<float>(mean);
            const double d = z0_ - static_cast<double>(b.z_ref_m);  // z0 about the stored reference
            b.z_wz = static_cast<float>(total[kWz] + w * d);
            b.z_wz2 = static_cast<float>(std::max(0.0, total[kWz2] + 2.0 * d * total[kWz] + w * d * d));
            if constexpr (!kCentred) {
                b.x_wx = static_cast<float>(total[kX1]);
                b.x_wx2 = static_cast<float>(total[kX2]);
                b.y_wy = static_cast<float>(total[kY1]);
                b.y_wy2 = static_cast<float>(total[kY2]);
            }
            if (!a.empty()) add_sums(b, a);
            a = b;
        } else {
            // The shares' z sums straight about the cell's reference, in double (add_sums
            // without the float cell it would build for them).
            const double d = z0_ - static_cast<double>(a.z_ref_m);
            const double wz = total[kWz] + w * d;
            a.w = static_cast<float>(a.w + w);
            a.z_wz = static_cast<float>(a.z_wz + wz);
            a.z_wz2 = static_cast<float>(a.z_wz2 + (total[kWz2] + d * (wz + total[kWz])));
            if constexpr (!kCentred) {
                a.x_wx = static_cast<float>(a.x_wx + total[kX1]);
                a.x_wx2 = static_cast<float>(a.x_wx2 + total[kX2]);
                a.y_wy = static_cast<float>(a.y_wy + total[kY1]);
                a.y_wy2 = static_cast<float>(a.y_wy2 + total[kY2]);
            }
        }
        CellTally& tally = cells.tallies[at];
        tally.count += static_cast<uint32_t>(total[kN] + 0.5);  // a whole number >= 1, exact in double
        tally.newest_ms = std::max(tally.newest_ms, newest_ms_);
        CellExtremes& own = extremes_[static_cast<std::size_t>(i) * static_cast<std::size_t>(columns_) +
                                      static_cast<std::size_t>(j)];
        tally.extremes.merge(own);
        own = CellExtremes{};
    }

    int rows_, columns_;
    std::size_t stride_, words_;  // words_: 64-bit words of a row of column bits
    std::vector<double> corner_storage_;
    Record* corners_;                     // (rows + 2) x (columns + 2), unwrapped; zero where nothing is pending
    Record* running_;                     // the running sums of the row above, per column; zero where not active
    std::vector<CellExtremes> extremes_;  // rows x columns: the pending points' own heights
    std::vector<uint64_t> spans_;         // per corner row, the columns its pending footprints span
    std::vector<uint64_t> active_;        // during flush(): the columns an open footprint covers
    bool pending_ = false;
    SpreadCorners corners_kernel_ = nullptr;  // the table's, taken at the first pending point
    double z0_ = 0.0;  // the pending heights are taken from the first one's
    TimeTick newest_ms_ = kNoTime;
    int row_lo_ = 0, row_hi_ = 0;  // the pending corners' rows
};

using SpreadSums = SpreadSumsOf<kCornerComponents>;
using SpreadSumsCentred = SpreadSumsOf<kCentredCornerComponents>;

}  // namespace ugv::terrain::detail
