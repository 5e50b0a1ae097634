#include "ugv/terrain/egocentric_grid.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "float4.hpp"

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
    const auto row = static_cast<std::size_t>(ny + 3);  // whole groups of four
    moved_.cells.resize(row);
    moved_.to.resize(row);
    moved_.centre_y.resize(row, 0.0f);
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

namespace {

using detail::Float4;
using detail::Int4;

// Rotation constants, broadcast once per transform.
struct Turn
{
    Float4 c, s, cc, ss;                  // cos, sin and their squares of the angle
    Float4 inv_g, g, y_min, nx, ny, nx_last, ny_last;
    Float4 row_shift, rows, row_stride;   // eq. 6: physical row = (i + m_i) mod nx
};

// Where a cell goes: its index in the working map, or one of these.
constexpr int32_t kDropped = -1;  // turned out of the map
constexpr int32_t kEmpty = -2;    // nothing to move

// Four cells (src[0..3]) of one row, at row_x (their centre's x minus the pivot's) and
// centre_y (minus the pivot's): where each goes (to) and its sums there (moved). Empty
// cells compute garbage that is never used. Branch-free.
void turn_cells(const Turn& t, const CellSums* src, Float4 row_x, Float4 centre_y, CellSums* moved, int32_t* to)
{
    Float4 w, x_wx, y_wy, z_wz, z_ref, x_wx2, y_wy2, z_wz2;
    std::memcpy(&w, &src[0].w, 16);
    std::memcpy(&x_wx, &src[1].w, 16);
    std::memcpy(&y_wy, &src[2].w, 16);
    std::memcpy(&z_wz, &src[3].w, 16);
    std::memcpy(&z_ref, &src[0].z_ref_m, 16);
    std::memcpy(&x_wx2, &src[1].z_ref_m, 16);
    std::memcpy(&y_wy2, &src[2].z_ref_m, 16);
    std::memcpy(&z_wz2, &src[3].z_ref_m, 16);
    detail::transpose4(w, x_wx, y_wy, z_wz);  // rows were cells, now each holds one sum of the four
    detail::transpose4(z_ref, x_wx2, y_wy2, z_wz2);
    const Float4 zero = detail::splat(0.0f);
    const Float4 inv_w = w > zero ? 1.0f / w : zero;  // an empty cell's w is NaN
    // Eq. 9-10: the element's position is its centre (eq. 17-18) plus its remainder.
    const Float4 x_re = x_wx * inv_w;
    const Float4 y_re = y_wy * inv_w;
    const Float4 x = row_x + x_re;
    const Float4 y = centre_y + y_re;
    // Eq. 11-14 in Cartesian form: the world stays, the frame turns by the angle.
    const Float4 xn = t.c * x + t.s * y;
    const Float4 yn = t.c * y - t.s * x;
    // Eq. 15-16 and 5-7: the new cell and the new remainders.
    const Float4 fx = xn * t.inv_g;
    const Float4 fy = (yn - t.y_min) * t.inv_g;
    const Int4 inside = (fx >= 0.0f) & (fx < t.nx) & (fy >= 0.0f) & (fy < t.ny);
    const Float4 i = __builtin_convertvector(__builtin_convertvector(detail::min4(detail::max4(fx, zero), t.nx_last), Int4), Float4);
    const Float4 j = __builtin_convertvector(__builtin_convertvector(detail::min4(detail::max4(fy, zero), t.ny_last), Int4), Float4);
    const Float4 x_rel = xn - (i + 0.5f) * t.g;
    const Float4 y_rel = yn - t.y_min - (j + 0.5f) * t.g;
    Float4 row = i + t.row_shift;
    row = row >= t.rows ? row - t.rows : row;
    const Int4 cell = __builtin_convertvector(row * t.row_stride + j, Int4);
    const Int4 empty = z_ref != z_ref;  // NaN reference: an empty cell
    detail::store4(to, empty ? Int4{} + kEmpty : (inside ? cell : Int4{} + kDropped));
    // The samples' spread about their mean, turned with the frame (the x-y covariance is
    // not kept, so the two variances mix by cos^2 and sin^2).
    const Float4 var_x = detail::max4(x_wx2 * inv_w - x_re * x_re, zero);
    const Float4 var_y = detail::max4(y_wy2 * inv_w - y_re * y_re, zero);
    x_wx = w * x_rel;
    y_wy = w * y_rel;
    x_wx2 = w * (t.cc * var_x + t.ss * var_y + x_rel * x_rel);
    y_wy2 = w * (t.ss * var_x + t.cc * var_y + y_rel * y_rel);
    detail::transpose4(w, x_wx, y_wy, z_wz);  // back to one cell per vector
    detail::transpose4(z_ref, x_wx2, y_wy2, z_wz2);
    std::memcpy(&moved[0].w, &w, 16);
    std::memcpy(&moved[1].w, &x_wx, 16);
    std::memcpy(&moved[2].w, &y_wy, 16);
    std::memcpy(&moved[3].w, &z_wz, 16);
    std::memcpy(&moved[0].z_ref_m, &z_ref, 16);
    std::memcpy(&moved[1].z_ref_m, &x_wx2, 16);
    std::memcpy(&moved[2].z_ref_m, &y_wy2, 16);
    std::memcpy(&moved[3].z_ref_m, &z_wz2, 16);
}

}  // namespace

int EgocentricGrid::transform(double angle_rad, double pivot_x_m, double pivot_y_m)
{
    // working_ is all empty here: each row of the current map is cleared once it has been
    // read, so after the swap the old map is the next (empty) working map without a pass
    // of its own. One cos and sin per rotation: every cell turns by the same angle, so this
    // is the trigonometric lookup of section 3.4 reduced to a single entry.
    const float c = static_cast<float>(std::cos(angle_rad));
    const float s = static_cast<float>(std::sin(angle_rad));
    Turn t;
    t.c = detail::splat(c);
    t.s = detail::splat(s);
    t.cc = detail::splat(c * c);
    t.ss = detail::splat(s * s);
    t.inv_g = detail::splat(inv_g_);
    t.g = detail::splat(static_cast<float>(grid_m_));
    t.y_min = detail::splat(y_min_f_);
    t.nx = detail::splat(nx_f_);
    t.ny = detail::splat(ny_f_);
    t.nx_last = detail::splat(nx_f_ - 0.5f);
    t.ny_last = detail::splat(ny_f_ - 0.5f);
    t.row_shift = detail::splat(static_cast<float>(m_i_));
    t.rows = detail::splat(nx_f_);
    t.row_stride = detail::splat(ny_f_);
    const float px = static_cast<float>(pivot_x_m), py = static_cast<float>(pivot_y_m);
    // The cell centres' y minus the pivot's, padded to whole groups of four.
    float* centre_y = moved_.centre_y.data();
    for (int j = 0; j < ny_; ++j) centre_y[j] = centre_y_m_[static_cast<std::size_t>(j)] - py;
    CellSums* moved = moved_.cells.data();
    int32_t* to = moved_.to.data();
    CellSums* working = working_.sums_data();
    uint32_t* working_count = working_.counts_data();
    int dropped = 0;
    for (int pr = 0; pr < nx_; ++pr) {
        int i = pr - m_i_;
        if (i < 0) i += nx_;
        const Float4 row_x = detail::splat(centre_x_m_[static_cast<std::size_t>(i)] - px);
        const int first = pr * ny_;
        CellSums* row = &cells_.sums(first);
        const uint32_t* row_count = &cells_.count(first);
        int j = 0;
        for (; j + 4 <= ny_; j += 4) {
            // Unknown ground is most of a real map (the demo's holds 37 % known cells): four
            // empty cells in a row skip the arithmetic.
            if (row[j].empty() && row[j + 1].empty() && row[j + 2].empty() && row[j + 3].empty()) {
                detail::store4(to + j, detail::Int4{} + kEmpty);
                continue;
            }
            turn_cells(t, row + j, row_x, detail::load4(centre_y + j), moved + j, to + j);
        }
        if (j < ny_) {
            CellSums tail[4];  // the last 1-3 cells, padded with empty ones
            std::copy(row + j, row + ny_, tail);
            turn_cells(t, tail, row_x, detail::load4(centre_y + j), moved + j, to + j);
        }
        // Accumulate into the working map (cells that merge add their sums).
        for (j = 0; j < ny_; ++j) {
            const int dst = to[j];
            if (dst < 0) {
                dropped += dst == kDropped;
                continue;
            }
            if (working[dst].empty()) {
                working[dst] = moved[j];
                working_count[dst] = row_count[j];
            } else {
                working_.add(dst, moved[j], row_count[j]);
            }
        }
        cells_.clear(static_cast<std::size_t>(first), static_cast<std::size_t>(ny_));
    }
    cells_.swap(working_);
    return dropped;
}

}  // namespace ugv::terrain
