#include "ugv/terrain/egocentric_grid.hpp"

#include <algorithm>
#include <cmath>

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
}

void EgocentricGrid::clear()
{
    std::fill(cells_.begin(), cells_.end(), CellSums{});
    m_i_ = 0;
}

void EgocentricGrid::wrap_forward(int rows)
{
    if (rows <= 0) return;
    rows = std::min(rows, nx_);
    for (int r = 0; r < rows; ++r) {
        const auto first = cells_.begin() + static_cast<std::ptrdiff_t>(physical(r, 0));
        std::fill(first, first + ny_, CellSums{});
    }
    m_i_ = (m_i_ + rows) % nx_;
}

void EgocentricGrid::wrap_backward(int rows)
{
    if (rows <= 0) return;
    rows = std::min(rows, nx_);
    m_i_ = ((m_i_ - rows) % nx_ + nx_) % nx_;
    for (int r = 0; r < rows; ++r) {
        const auto first = cells_.begin() + static_cast<std::ptrdiff_t>(physical(r, 0));
        std::fill(first, first + ny_, CellSums{});
    }
}

int EgocentricGrid::transform(double angle_rad, double pivot_x_m, double pivot_y_m)
{
    // working_ is all zero here: each cell of the current map is cleared as it is read, so
    // after the swap the old map is the next (empty) working map without a separate pass.
    // One cos and sin per rotation: every cell turns by the same angle, so this is the
    // trigonometric lookup of section 3.4 reduced to a single entry.
    const float c = static_cast<float>(std::cos(angle_rad));
    const float s = static_cast<float>(std::sin(angle_rad));
    const float cc = c * c, ss = s * s;
    const float px = static_cast<float>(pivot_x_m), py = static_cast<float>(pivot_y_m);
    int dropped = 0;
    // Cells are handled in chunks: the first pass computes where each goes and prefetches
    // that cell of the working map (1.4 MB: not in L2), the second accumulates.
    constexpr int kChunk = 64;
    CellSums moved[kChunk];
    int dst[kChunk];
    float x_new[kChunk], y_new[kChunk], var_x_new[kChunk], var_y_new[kChunk];
    int m = 0;
    auto accumulate = [&] {
        for (int q = 0; q < m; ++q) {
            const CellSums& src = moved[q];
            CellSums& d = working_[static_cast<std::size_t>(dst[q])];
            d.z_w += src.z_w;
            d.z_wz += src.z_wz;
            d.z_wz2 += src.z_wz2;
            d.x_w += src.x_w;
            d.x_wx += src.x_w * x_new[q];
            d.x_wx2 += src.x_w * (var_x_new[q] + x_new[q] * x_new[q]);
            d.y_w += src.y_w;
            d.y_wy += src.y_w * y_new[q];
            d.y_wy2 += src.y_w * (var_y_new[q] + y_new[q] * y_new[q]);
            d.n += src.n;
        }
        m = 0;
    };
    for (int pr = 0; pr < nx_; ++pr) {
        int i = pr - m_i_;
        if (i < 0) i += nx_;
        const float row_x = centre_x_m_[static_cast<std::size_t>(i)] - px;
        CellSums* row = &cells_[static_cast<std::size_t>(pr) * static_cast<std::size_t>(ny_)];
        for (int j = 0; j < ny_; ++j) {
            if (row[j].n == 0) continue;
            const CellSums src = row[j];
            row[j] = CellSums{};
            // Eq. 9-10: the element's position is its centre (eq. 17-18) plus its remainder.
            const float inv_xw = src.x_w > 0.0f ? 1.0f / src.x_w : 0.0f;
            const float inv_yw = src.y_w > 0.0f ? 1.0f / src.y_w : 0.0f;
            const float x_re = src.x_wx * inv_xw;
            const float y_re = src.y_wy * inv_yw;
            const float x = row_x + x_re;
            const float y = centre_y_m_[static_cast<std::size_t>(j)] - py + y_re;
            // Eq. 11-14 in Cartesian form: the world stays, the frame turns by angle.
            const float xn = c * x + s * y;
            const float yn = -s * x + c * y;
            float x_rel = 0.0f, y_rel = 0.0f;
            const int to = locate(xn, yn, x_rel, y_rel);  // eq. 15-16: x_rel, y_rel are the new remainders
            if (to < 0) {
                ++dropped;
                continue;
            }
            __builtin_prefetch(&working_[static_cast<std::size_t>(to)], 1);
            // The samples' spread about their mean, turned with the frame (the x-y
            // covariance is not kept, so the two variances mix by cos^2 and sin^2).
            const float var_x = std::max(0.0f, src.x_wx2 * inv_xw - x_re * x_re);
            const float var_y = std::max(0.0f, src.y_wy2 * inv_yw - y_re * y_re);
            moved[m] = src;
            dst[m] = to;
            x_new[m] = x_rel;
            y_new[m] = y_rel;
            var_x_new[m] = cc * var_x + ss * var_y;
            var_y_new[m] = ss * var_x + cc * var_y;
            if (++m == kChunk) accumulate();
        }
    }
    accumulate();
    cells_.swap(working_);
    return dropped;
}

}  // namespace ugv::terrain
