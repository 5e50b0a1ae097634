// The report's wrappable grid (sections 3.2-3.4). The grid's local frame has X along the
// map heading and Y to the left; row i (unwrapped) covers x in [i G, (i+1) G), column j
// covers y in [y_min + j G, y_min + (j+1) G) with y_min = -ny G / 2 (centred: see
// docs/ARCHITECTURE.md, "Corrections to the report's equations").
// Rows are stored as a ring: unwrapped row i lives in physical row (i + m_i) mod nx
// (eq. 5-6), so a forward wrap is an index update plus clearing the rows left behind.
// Columns are a ring too, by m_j, so a sideways re-centre by whole columns is likewise an
// index update plus clearing the columns that leave; a rotation writes its new grid with
// m_j = 0. Nothing outside the grid sees either index: every reader goes through
// physical(), and the snapshot is in unwrapped order.
//
// The sums of the known cells live in a pool, in no particular order; each cell holds the
// index of its sums there (its slot) or kNoSlot while it is empty.
// A rotation (eq. 9-16) then works on the pool in order, re-expressing each cell's sums
// where they are, and moves only the 4-byte slots into the working index grid: the cells'
// 32 bytes of sums never move, nor do the other per-cell quantities kept per slot
// (cell_array.hpp), and unknown ground costs nothing.
#pragma once

#include <cstdint>
#include <vector>

#include "ugv/terrain/cell_array.hpp"

namespace ugv::terrain {

class EgocentricGrid
{
public:
    EgocentricGrid(int nx, int ny, double grid_size_m);

    int nx() const { return nx_; }
    int ny() const { return ny_; }
    double grid_size_m() const { return grid_m_; }
    double y_min_m() const { return y_min_m_; }
    int wrap_index() const { return m_i_; }
    int column_index() const { return m_j_; }  // m_j: physical column = (j + m_j) mod ny

    // Hot path: the cell at local (x, y) and the position's offset from its centre.
    // Returns -1 outside the grid (never wrapped in: it would alias onto the far side).
    int locate(float x_m, float y_m, float& x_rel_m, float& y_rel_m) const
    {
        const float fx = x_m * inv_g_;
        const float fy = (y_m - y_min_f_) * inv_g_;
        if (!(fx >= 0.0f && fx < nx_f_ && fy >= 0.0f && fy < ny_f_)) return -1;
        const int i = static_cast<int>(fx);
        const int j = static_cast<int>(fy);
        x_rel_m = x_m - centre_x_m_[i];
        y_rel_m = y_m - centre_y_m_[j];
        return physical(i, j);
    }
    // Cell index of unwrapped (row i, column j) (eq. 6, and its like for columns).
    // Branch-free: it is in the fusion loop.
    int physical(int i, int j) const
    {
        const int r = i + m_i_, c = j + m_j_;
        return (r - nx_ * (r >= nx_)) * ny_ + (c - ny_ * (c >= ny_));
    }
    // An empty cell's sums are those of CellSums{} (and its count 0).
    const CellSums& at(int cell) const
    {
        const uint32_t s = slot_[static_cast<std::size_t>(cell)];
        return s == kNoSlot ? kEmptyCell : pool_.sums(static_cast<int>(s));
    }
    const CellSums& at(int i, int j) const { return at(physical(i, j)); }
    // Count 0 and NaN heights for an empty cell.
    const CellTally& tally(int cell) const
    {
        const uint32_t s = slot_[static_cast<std::size_t>(cell)];
        return s == kNoSlot ? kNoTally : pool_.tally(static_cast<int>(s));
    }
    const CellTally& tally(int i, int j) const { return tally(physical(i, j)); }
    uint32_t count(int cell) const { return tally(cell).count; }
    uint32_t count(int i, int j) const { return tally(i, j).count; }
    const CellExtremes& extremes(int cell) const { return tally(cell).extremes; }
    const CellExtremes& extremes(int i, int j) const { return tally(i, j).extremes; }
    void fuse(int cell, float x_rel_m, float y_rel_m, double z_m, float w, TimeTick t_ms)
    {
        pool_.fuse(static_cast<int>(storage_of(cell)), x_rel_m, y_rel_m, z_m, w, t_ms);
    }
    // For the fusion loop: where in cells() the cell's sums and count are, given a slot if
    // it had none. The pool does not grow, so pointers into cells() stay valid.
    uint32_t storage_of(int cell)
    {
        const uint32_t s = slot_[static_cast<std::size_t>(cell)];
        return s != kNoSlot ? s : take_slot(cell);
    }
    CellArray& cells() { return pool_; }
    // The number of known cells (the pool's slots in use).
    int known_cells() const { return static_cast<int>(used_ - free_count_); }
    // Eq. 17-18: the cell centres, precomputed.
    float centre_x_m(int i) const { return centre_x_m_[static_cast<std::size_t>(i)]; }
    float centre_y_m(int j) const { return centre_y_m_[static_cast<std::size_t>(j)]; }

    // The map moved forward by rows cells: the rows behind (unwrapped 0 .. rows-1) are
    // cleared and become the far rows; m_i advances (eq. 8, as many rows as were driven).
    void wrap_forward(int rows);
    // Reversing: the far rows are cleared and become the near rows; m_i goes back.
    void wrap_backward(int rows);

    // The frame moved sideways by whole columns (to the left for columns > 0): the content
    // moves by -columns, the columns that leave are cleared and become those on the other
    // side; m_j follows. The same map as transform(0, 0, columns G), without moving a cell.
    // Returns the number of known cells cleared (those the transform would drop).
    int shift_columns(int columns);

    // Rigid re-anchoring of the whole map (eq. 9-16): a cell's content at local p moves to
    // R(-angle) (p - pivot). Each cell's position is its centre plus its remainder (the
    // mean offset of its samples); the sums are re-expressed about the new cell's centre
    // and accumulated into the working grid, which then becomes the current one. Returns
    // the number of non-empty cells that fell outside and were dropped.
    int transform(double angle_rad, double pivot_x_m, double pivot_y_m);

    // The same rotation as transform(), cell by cell in double, written as the report puts
    // it (rotation_reference.cpp): the specification that transform()'s vector kernels are
    // tested against, not for the hot path. The cells landing together are merged in
    // unwrapped order and the pool is rebuilt in that order. near_edge, if given, is set per
    // physical cell: 1 where a cell landed within 0.005 cells of a cell edge, where the
    // kernels' float arithmetic may bin it into the neighbour.
    int transform_reference(double angle_rad, double pivot_x_m, double pivot_y_m,
                            std::vector<uint8_t>* near_edge = nullptr);

    void clear();

private:
    static constexpr uint32_t kNoSlot = 0xffffffffu;
    static const CellSums kEmptyCell;
    static const CellTally kNoTally;

    uint32_t take_slot(int cell);
    // Empties slot s and lists it free. Does not touch the index of the cell it belonged to.
    void free_slot(uint32_t s);
    // Moves the last slots in use into the free ones below them, once a quarter of the slots
    // below used_ are free (the rotation works on all of them).
    void compact_if_sparse();
    void clear_rows(int first_unwrapped_row, int rows);
    // Returns the number of known cells cleared.
    int clear_columns(int first_unwrapped_column, int columns);

    int nx_, ny_;
    double grid_m_, y_min_m_;
    float inv_g_, y_min_f_, nx_f_, ny_f_;
    int m_i_ = 0, m_j_ = 0;
    std::vector<float> centre_x_m_, centre_y_m_;
    // The pool: slots 0 .. used_ - 1 hold the known cells' sums and counts, in no particular
    // order, and free slots (empty sums, any count: the first free_count_ of free_ list them);
    // every slot from used_ on is empty and free, with 8 more than the cells so that the
    // rotation reads whole groups of eight. home_[s] is the cell whose sums slot s holds
    // (a physical index; any value in a free slot).
    CellArray pool_;
    std::vector<uint32_t> home_;
    uint32_t used_ = 0;
    std::vector<uint32_t> free_;
    uint32_t free_count_ = 0;
    // Per physical cell: its slot, or kNoSlot. working_slot_ is the index grid a rotation
    // fills; between rotations it holds nothing of use.
    std::vector<uint32_t> slot_, working_slot_;
    // Scratch of transform(), allocated once: the slots that landed on a cell already
    // taken (merged into its slot, then freed), and a bit a slot for those placed.
    std::vector<uint32_t> merge_from_, merge_into_;
    std::vector<uint8_t> placed_;
};

}  // namespace ugv::terrain
