#include "ugv/terrain/egocentric_grid.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "kernels/kernel_table.hpp"

namespace ugv::terrain {

const CellSums EgocentricGrid::kEmptyCell{};
const CellTally EgocentricGrid::kNoTally{};

namespace {

// The rotation finds a cell's row from its index in float (turn_slots.cpp), exactly below
// 2^22 cells; 2048 x 2048 is far beyond any map this mapper is meant for.
std::size_t checked_cells(int nx, int ny)
{
    if (nx < 1 || ny < 1 || static_cast<long long>(nx) * ny > (1LL << 22))
        throw std::invalid_argument("EgocentricGrid: " + std::to_string(nx) + " x " + std::to_string(ny) +
                                    " cells: need 1 to 4194304 cells");
    return static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
}

}  // namespace

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
      pool_(checked_cells(nx, ny) + 8),  // + 8: the rotation reads whole groups of eight slots
      home_(pool_.size(), 0),
      free_(pool_.size() - 8),
      slot_(pool_.size() - 8, kNoSlot),
      working_slot_(pool_.size() - 8, kNoSlot),
      merge_from_(pool_.size() - 8),
      merge_into_(pool_.size() - 8),
      placed_(pool_.size() / 8)
{
    static_assert(kNoSlot == detail::kNoSlot);
    for (int i = 0; i < nx; ++i) centre_x_m_[static_cast<std::size_t>(i)] = static_cast<float>((i + 0.5) * grid_m_);
    for (int j = 0; j < ny; ++j)
        centre_y_m_[static_cast<std::size_t>(j)] = static_cast<float>(y_min_m_ + (j + 0.5) * grid_m_);
}

uint32_t EgocentricGrid::take_slot(int cell)
{
    const uint32_t s = free_count_ > 0 ? free_[--free_count_] : used_++;
    // A free slot's sums are empty, but a rotation's arithmetic may have written NaN over
    // its zeros, and its count and extremes are any value.
    pool_.reset(static_cast<int>(s));
    home_[s] = static_cast<uint32_t>(cell);
    slot_[static_cast<std::size_t>(cell)] = s;
    return s;
}

inline void EgocentricGrid::free_slot(uint32_t s)
{
    pool_.sums(static_cast<int>(s)) = CellSums{};
    free_[free_count_++] = s;
}

void EgocentricGrid::compact_if_sparse()
{
    if (free_count_ * 4 <= used_) return;
    // Two ends: the lowest free slot takes the highest one in use, until they meet.
    const uint32_t known = used_ - free_count_;
    uint32_t low = 0, high = used_;
    while (true) {
        while (low < high && !pool_.sums(static_cast<int>(low)).empty()) ++low;
        while (high > low && pool_.sums(static_cast<int>(high - 1)).empty()) --high;
        if (low >= high) break;
        const int from = static_cast<int>(high - 1), to = static_cast<int>(low);
        pool_.move(to, from);
        home_[low] = home_[high - 1];
        slot_[home_[low]] = low;
        pool_.clear(high - 1, 1);
        --high;
    }
    used_ = known;
    free_count_ = 0;
}

void EgocentricGrid::clear()
{
    pool_.clear(0, used_);
    used_ = 0;
    free_count_ = 0;
    std::fill(slot_.begin(), slot_.end(), kNoSlot);
    m_i_ = 0;
    m_j_ = 0;
}

void EgocentricGrid::clear_rows(int first_unwrapped_row, int rows)
{
    for (int r = first_unwrapped_row; r < first_unwrapped_row + rows; ++r) {
        // The whole physical row: with the column ring its first cell is not physical(r, 0).
        const int first = physical(r, 0) / ny_ * ny_;
        for (int cell = first; cell < first + ny_; ++cell) {
            uint32_t& s = slot_[static_cast<std::size_t>(cell)];
            if (s == kNoSlot) continue;
            free_slot(s);
            s = kNoSlot;
        }
    }
    compact_if_sparse();
}

int EgocentricGrid::clear_columns(int first_unwrapped_column, int columns)
{
    int cleared = 0;
    for (int i = 0; i < nx_; ++i) {
        for (int j = first_unwrapped_column; j < first_unwrapped_column + columns; ++j) {
            uint32_t& s = slot_[static_cast<std::size_t>(physical(i, j))];
            if (s == kNoSlot) continue;
            free_slot(s);
            s = kNoSlot;
            ++cleared;
        }
    }
    compact_if_sparse();
    return cleared;
}

int EgocentricGrid::shift_columns(int columns)
{
    if (columns == 0) return 0;
    const int n = std::min(std::abs(columns), ny_);
    if (columns > 0) {
        // Unwrapped columns 0 .. n-1 leave on the right; they become the far left ones.
        const int cleared = clear_columns(0, n);
        m_j_ = (m_j_ + n) % ny_;
        return cleared;
    }
    const int cleared = clear_columns(ny_ - n, n);
    m_j_ = ((m_j_ - n) % ny_ + ny_) % ny_;
    return cleared;
}

void EgocentricGrid::wrap_forward(int rows)
{
    if (rows <= 0) return;
    rows = std::min(rows, nx_);
    clear_rows(0, rows);
    m_i_ = (m_i_ + rows) % nx_;
}

void EgocentricGrid::wrap_backward(int rows)
{
    if (rows <= 0) return;
    rows = std::min(rows, nx_);
    m_i_ = ((m_i_ - rows) % nx_ + nx_) % nx_;
    clear_rows(0, rows);
}

int EgocentricGrid::transform(double angle_rad, double pivot_x_m, double pivot_y_m)
{
    // One cos and sin per rotation: every cell turns by the same angle, so this is the
    // trigonometric lookup of section 3.4 reduced to a single entry. A cell of row i and
    // column j (unwrapped) has its centre at x = (i + 1/2) G, y = y_min + (j + 1/2) G (eq.
    // 17-18); about the pivot and turned, over G, that is c i + s j + offset_x along the new
    // rows and c j - s i + offset_y along the new columns (kernels/turn_slots.hpp).
    const double c = std::cos(angle_rad), s = std::sin(angle_rad);
    const double u = 0.5 - pivot_x_m / grid_m_;               // (centre_x(0) - pivot_x) / G
    const double v = 0.5 + (y_min_m_ - pivot_y_m) / grid_m_;  // (centre_y(0) - pivot_y) / G
    const detail::TurnConstants t{static_cast<float>(c),
                                  static_cast<float>(s),
                                  static_cast<float>(c / grid_m_),
                                  static_cast<float>(s / grid_m_),
                                  static_cast<float>(c * c),
                                  static_cast<float>(s * s),
                                  static_cast<float>(grid_m_),
                                  static_cast<float>(-0.5 * grid_m_),
                                  nx_f_,
                                  ny_f_,
                                  static_cast<float>(1.0 / ny_),
                                  static_cast<float>(m_i_),
                                  static_cast<float>(m_i_) * ny_f_,
                                  static_cast<float>(m_j_),
                                  static_cast<float>(c * u + s * v),
                                  static_cast<float>(c * v - s * u - y_min_m_ / grid_m_),
                                  nx_ * ny_};
    // The working index grid starts with no cell taken.
    std::fill(working_slot_.begin(), working_slot_.end(), kNoSlot);
    // The kernel empties the slots of the cells it turns out of the map and lists them free
    // (free_ has room for every slot, and so have the merge lists).
    detail::TurnTarget target{working_slot_.data(), placed_.data(), free_.data() + free_count_};
    const detail::KernelTable& kernels = detail::kernels();
    kernels.turn_slots(t, pool_.sums_data(), home_.data(), used_, target);
    const int merges = kernels.find_merges(working_slot_.data(), home_.data(), placed_.data(), used_,
                                           merge_from_.data(), merge_into_.data());
    slot_.swap(working_slot_);
    m_j_ = 0;  // the kernel wrote the turned cells with no column shift
    // The kernel listed the dropped slots after the free ones: count them in before the
    // merges list theirs.
    free_count_ += static_cast<uint32_t>(target.drops);
    // The cells that landed on a cell already taken (~1 % of a full map's at 5 deg) pool
    // their sums and counts with it and leave free slots.
    for (int m = 0; m < merges; ++m) {
        const uint32_t from = merge_from_[static_cast<std::size_t>(m)];
        pool_.merge(static_cast<int>(merge_into_[static_cast<std::size_t>(m)]), static_cast<int>(from));
        free_slot(from);
    }
    compact_if_sparse();
    return target.drops;
}

}  // namespace ugv::terrain
