// The comparison mode (docs/ARCHITECTURE.md, "The world-aligned mode"): a square grid on
// the ENU axes, stored as a 2-D ring buffer (as grid_map does), that follows the vehicle by
// whole cells and never rotates.
// Its local frame has its origin at the south-west corner of the window, so the hot loop
// works in small float coordinates.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "ugv/terrain/cell_array.hpp"

namespace ugv::terrain {

class WorldGrid
{
public:
    WorldGrid(int n, double grid_size_m);

    int size() const { return n_; }
    // Physical row and column of the window's corner (the ring offsets).
    int ring_row() const { return ring_i_; }
    int ring_column() const { return ring_j_; }
    int nx() const { return n_; }
    int ny() const { return n_; }
    double y_min_m() const { return 0.0; }
    double grid_size_m() const { return grid_m_; }
    // ENU position of the window's south-west corner (m).
    Eigen::Vector2d corner_m() const { return {static_cast<double>(corner_i_) * grid_m_, static_cast<double>(corner_j_) * grid_m_}; }

    // Moves the window so that it is centred on centre_m (ENU); the rows and columns that
    // leave are cleared. Returns the number of rows plus columns shifted.
    int follow(const Eigen::Vector2d& centre_m);

    // Hot path: local = ENU - corner. -1 outside the window.
    int locate(float x_m, float y_m, float& x_rel_m, float& y_rel_m) const
    {
        const float fx = x_m * inv_g_;
        const float fy = y_m * inv_g_;
        if (!(fx >= 0.0f && fx < n_f_ && fy >= 0.0f && fy < n_f_)) return -1;
        const int i = static_cast<int>(fx);
        const int j = static_cast<int>(fy);
        x_rel_m = x_m - (static_cast<float>(i) + 0.5f) * g_f_;
        y_rel_m = y_m - (static_cast<float>(j) + 0.5f) * g_f_;
        return physical(i, j);
    }
    // Cell index of window-relative (i east, j north). Branch-free: it is in the fusion loop.
    int physical(int i, int j) const
    {
        const int r = i + ring_i_;
        const int c = j + ring_j_;
        return (r - n_ * (r >= n_)) * n_ + (c - n_ * (c >= n_));
    }
    const CellSums& at(int cell) const { return cells_.sums(cell); }
    const CellTally& tally(int cell) const { return cells_.tally(cell); }
    uint32_t count(int cell) const { return cells_.count(cell); }
    void fuse(int cell, float x_rel_m, float y_rel_m, double z_m, float w, TimeTick t_ms)
    {
        cells_.fuse(cell, x_rel_m, y_rel_m, z_m, w, t_ms);
    }
    CellArray& cells() { return cells_; }
    // Where in cells() the cell's sums and count are (the same index: see EgocentricGrid).
    uint32_t storage_of(int cell) const { return static_cast<uint32_t>(cell); }
    // The cell holding ENU position p (m), or -1 outside the window.
    int cell_at(const Eigen::Vector2d& p_m) const;

    void clear();

private:
    void clear_row(int i);
    void clear_column(int j);

    int n_;
    double grid_m_;
    float inv_g_, g_f_, n_f_;
    bool placed_ = false;
    int64_t corner_i_ = 0, corner_j_ = 0;  // world cell index of the window's corner
    int ring_i_ = 0, ring_j_ = 0;          // physical row/column of the corner
    CellArray cells_;
};

}  // namespace ugv::terrain
