#include "ugv/terrain/world_grid.hpp"

#include <algorithm>
#include <cmath>

namespace ugv::terrain {

WorldGrid::WorldGrid(int n, double grid_size_m)
    : n_(n),
      grid_m_(grid_size_m),
      inv_g_(static_cast<float>(1.0 / grid_size_m)),
      g_f_(static_cast<float>(grid_size_m)),
      n_f_(static_cast<float>(n)),
      cells_(static_cast<std::size_t>(n) * static_cast<std::size_t>(n))
{
}

void WorldGrid::clear()
{
    cells_.clear();
    placed_ = false;
}

void WorldGrid::clear_row(int i)
{
    const int r = (i + ring_i_) % n_;
    cells_.clear(static_cast<std::size_t>(r) * static_cast<std::size_t>(n_), static_cast<std::size_t>(n_));
}

void WorldGrid::clear_column(int j)
{
    const int c = (j + ring_j_) % n_;
    for (int r = 0; r < n_; ++r) cells_.clear(static_cast<std::size_t>(r * n_ + c), 1);
}

static int wrap_mod(int64_t a, int n)
{
    const int64_t m = a % n;
    return static_cast<int>(m < 0 ? m + n : m);
}

int WorldGrid::follow(const Eigen::Vector2d& centre_m)
{
    const int64_t want_i = static_cast<int64_t>(std::floor(centre_m.x() / grid_m_)) - n_ / 2;
    const int64_t want_j = static_cast<int64_t>(std::floor(centre_m.y() / grid_m_)) - n_ / 2;
    if (!placed_) {
        placed_ = true;
        corner_i_ = want_i;
        corner_j_ = want_j;
        ring_i_ = wrap_mod(want_i, n_);
        ring_j_ = wrap_mod(want_j, n_);
        return 0;
    }
    const int64_t di = want_i - corner_i_, dj = want_j - corner_j_;
    if (di == 0 && dj == 0) return 0;
    if (std::abs(di) >= n_ || std::abs(dj) >= n_) {
        cells_.clear();
    } else {
        // The rows that leave on one side are the ones that enter on the other: clear them
        // (in window coordinates of the old corner) before moving the corner.
        for (int64_t k = 0; k < std::abs(di); ++k) clear_row(static_cast<int>(di > 0 ? k : n_ - 1 - k));
        for (int64_t k = 0; k < std::abs(dj); ++k) clear_column(static_cast<int>(dj > 0 ? k : n_ - 1 - k));
    }
    corner_i_ = want_i;
    corner_j_ = want_j;
    ring_i_ = wrap_mod(want_i, n_);
    ring_j_ = wrap_mod(want_j, n_);
    return static_cast<int>(std::min<int64_t>(std::abs(di) + std::abs(dj), 1 << 30));
}

int WorldGrid::cell_at(const Eigen::Vector2d& p_m) const
{
    const double fx = (p_m.x() - static_cast<double>(corner_i_) * grid_m_) / grid_m_;
    const double fy = (p_m.y() - static_cast<double>(corner_j_) * grid_m_) / grid_m_;
    if (!(fx >= 0.0 && fx < n_ && fy >= 0.0 && fy < n_)) return -1;
    return physical(static_cast<int>(fx), static_cast<int>(fy));
}

}  // namespace ugv::terrain
