#include "ugv/terrain/egocentric_grid.hpp"

#include <algorithm>
#include <cmath>

#include "turn_end.hpp"
#include "turn_row.hpp"

namespace ugv::terrain {

EgocentricGrid::EgocentricGrid(int nx, int ny, double grid_size_m)
    : nx_(nx),
      ny_(ny),
      grid_m_(grid_size_m),
      y_min_m_(-0.5 * ny * grid_size_m),
      inv_g_(static_cast<float>(1.0 / grid_size_m)),
      y_min_f_(static_cast<float>(y_min_m_)),
      nx_f_(static_cast<float>(nx)),
      ny_f_(static_cast<float>(ny)),
      centre_x_m_(static_cast<std::size_t>(nx)),
      centre_y_m_(static_cast<std::size_t>(ny)),
      cells_(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny)),
      working_(cells_.size())
{
    for (int i = 0; i < nx; ++i) centre_x_m_[static_cast<std::size_t>(i)] = static_cast<float>((i + 0.5) * grid_m_);
    for (int j = 0; j < ny; ++j)
        centre_y_m_[static_cast<std::size_t>(j)] = static_cast<float>(y_min_m_ + (j + 0.5) * grid_m_);
    const auto row = static_cast<std::size_t>((ny + 7) / 8 * 8);  // whole groups of eight
    turn_.column_x.resize(row, 0.0f);
    turn_.column_y.resize(row, 0.0f);
    turn_.merge_sums.resize(row);
    turn_.merge_counts.resize(row);
    turn_.merge_to.resize(row);
    turn_.held.resize(static_cast<std::size_t>(nx) * static_cast<std::size_t>(detail::held_row_bytes(ny)), 0);
    turn_.turned.resize(turn_.held.size(), 0);
}

void EgocentricGrid::clear()
{
    cells_.clear();
    m_i_ = 0;
}

void EgocentricGrid::wrap_forward(int rows)
{
    if (rows <= 0) return;
    rows = std::min(rows, nx_);
    for (int r = 0; r < rows; ++r)
        cells_.clear(static_cast<std::size_t>(physical(r, 0)), static_cast<std::size_t>(ny_));
    m_i_ = (m_i_ + rows) % nx_;
}

void EgocentricGrid::wrap_backward(int rows)
{
    if (rows <= 0) return;
    rows = std::min(rows, nx_);
    m_i_ = ((m_i_ - rows) % nx_ + nx_) % nx_;
    for (int r = 0; r < rows; ++r)
        cells_.clear(static_cast<std::size_t>(physical(r, 0)), static_cast<std::size_t>(ny_));
}

int EgocentricGrid::transform(double angle_rad, double pivot_x_m, double pivot_y_m)
{
    // The working map holds the map turned last time: stale sums, never read, and counts
    // all 0 (the kernel zeroed them as it read them then). A cell that lands where the count
    // is still 0 overwrites the sums whole (a store, no load: the maps do not fit the L2
    // cache, and a load there stalled the loop on every cell); one that lands on a cell
    // already taken is merged after its row; the cells nothing landed on are made empty at
    // the end.
    //
    // One cos and sin per rotation: every cell turns by the same angle, so this is the
    // trigonometric lookup of section 3.4 reduced to a single entry.
    const float c = static_cast<float>(std::cos(angle_rad));
    const float s = static_cast<float>(std::sin(angle_rad));
    const detail::TurnConstants t{c * inv_g_,
                                  s * inv_g_,
                                  c * c,
                                  s * s,
                                  static_cast<float>(grid_m_),
                                  -0.5f * static_cast<float>(grid_m_),
                                  nx_f_,
                                  ny_f_,
                                  static_cast<float>(m_i_) * ny_f_,
                                  nx_ * ny_};
    const detail::TurnRow turn_row = detail::turn_row_kernel();
    const float px = static_cast<float>(pivot_x_m), py = static_cast<float>(pivot_y_m);
    // A cell at (x, y) from the pivot turns to the new row and column (in cells)
    //   f_x = (c x + s y) / g,  f_y = (c y - s x - y_min) / g,
    // with x = row's centre + x_re and y = column's centre + y_re: the centres' parts are
    // one number per row and one per column.
    float* column_x = turn_.column_x.data();
    float* column_y = turn_.column_y.data();
    for (int j = 0; j < ny_; ++j) {
        const float y = centre_y_m_[static_cast<std::size_t>(j)] - py;
        column_x[j] = s * y * inv_g_;
        column_y[j] = (c * y - y_min_f_) * inv_g_;
    }
    CellSums* working = working_.sums_data();
    uint32_t* taken = working_.counts_data();
    const auto row_bytes = static_cast<std::size_t>(detail::held_row_bytes(ny_));
    detail::TurnTarget target{working,
                              taken,
                              turn_.merge_sums.data(),
                              turn_.merge_counts.data(),
                              turn_.merge_to.data()};
    for (int pr = 0; pr < nx_; ++pr) {
        int i = pr - m_i_;
        if (i < 0) i += nx_;
        const int first = pr * ny_;
        const float x = centre_x_m_[static_cast<std::size_t>(i)] - px;
        target.known_row = turn_.turned.data() + static_cast<std::size_t>(pr) * row_bytes;
        turn_row(t, &cells_.sums(first), &cells_.count(first), ny_, c * x * inv_g_, s * x * inv_g_, column_x, column_y,
                 target);
        for (int m = 0; m < target.merges; ++m)  // ~1 % of the cells at 5 deg
            working_.add(target.merge_to[m], target.merge_sums[m], target.merge_counts[m]);
        target.merges = 0;
    }
    // The cells nothing landed on (count 0) still hold the sums of the map turned last time
    // where that map held sums (its known bits, kept from then): most of the cells nothing
    // lands on are unknown ground that was unknown then too, and need no write, and the
    // sums, out of the cache by now, are not read to find out.
    detail::clear_unlanded_kernel()(working, taken, turn_.held.data(), nx_, ny_);
    turn_.held.swap(turn_.turned);  // the map just turned is the next working map
    cells_.swap(working_);
    return target.turned_out;
}

}  // namespace ugv::terrain
