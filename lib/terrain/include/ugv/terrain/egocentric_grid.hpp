// The report's wrappable grid (sections 3.2-3.4). The grid's local frame has X along the
// map heading and Y to the left; row i (unwrapped) covers x in [i G, (i+1) G), column j
// covers y in [y_min + j G, y_min + (j+1) G) with y_min = -ny G / 2 (centred, DESIGN §7).
// Rows are stored as a ring: unwrapped row i lives in physical row (i + m_i) mod nx
// (eq. 5-6), so a forward wrap is an index update plus clearing the rows left behind.
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
    // Cell index of unwrapped (row i, column j) (eq. 6). Branch-free: it is in the fusion loop.
    int physical(int i, int j) const
    {
        const int r = i + m_i_;
        return (r - nx_ * (r >= nx_)) * ny_ + j;
    }
    const CellSums& at(int cell) const { return cells_.sums(cell); }
    const CellSums& at(int i, int j) const { return at(physical(i, j)); }
    uint32_t count(int cell) const { return cells_.count(cell); }
    uint32_t count(int i, int j) const { return count(physical(i, j)); }
    void fuse(int cell, float x_rel_m, float y_rel_m, double z_m, float w) { cells_.fuse(cell, x_rel_m, y_rel_m, z_m, w); }
    CellArray& cells() { return cells_; }
    // Eq. 17-18: the cell centres, precomputed.
    float centre_x_m(int i) const { return centre_x_m_[static_cast<std::size_t>(i)]; }
    float centre_y_m(int j) const { return centre_y_m_[static_cast<std::size_t>(j)]; }

    // The map moved forward by rows cells: the rows behind (unwrapped 0 .. rows-1) are
    // cleared and become the far rows; m_i advances (eq. 8, as many rows as were driven).
    void wrap_forward(int rows);
    // Reversing: the far rows are cleared and become the near rows; m_i goes back.
    void wrap_backward(int rows);

    // Rigid re-anchoring of the whole map (eq. 9-16): a cell's content at local p moves to
    // R(-angle) (p - pivot). Each cell's position is its centre plus its remainder (the
    // mean offset of its samples); the sums are re-expressed about the new cell's centre
    // and accumulated into the working grid, which then becomes the current one. Returns
    // the number of non-empty cells that fell outside and were dropped.
    int transform(double angle_rad, double pivot_x_m, double pivot_y_m);

    void clear();

private:
    int nx_, ny_;
    double grid_m_, y_min_m_;
    float inv_g_, y_min_f_, nx_f_, ny_f_;
    int m_i_ = 0;
    std::vector<float> centre_x_m_, centre_y_m_;
    // working_ holds the map before the last rotation: stale sums, overwritten or cleared
    // by the next one, and counts all 0 (see transform).
    CellArray cells_, working_;
    // Scratch of transform(), allocated once.
    struct TurnScratch
    {
        // Per column j, in cells: the part of a turned cell's new row and column that comes
        // from its column's centre (see transform).
        std::vector<float> column_x, column_y;
        // Cells of one row that landed on a cell already written: merged after the row.
        std::vector<CellSums> merge_sums;
        std::vector<uint32_t> merge_counts;
        std::vector<int32_t> merge_to;
        // Which cells hold sums, a bit a cell, whole 32-bit words a row: of the working map
        // (held, known from the kernel when the working map was the one turned), and of the
        // map being turned (turned).
        std::vector<uint8_t> held, turned;
    } turn_;
};

}  // namespace ugv::terrain
