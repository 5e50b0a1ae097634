// One row of the egocentric map's rotation (eq. 9-16), in two builds of the same steps:
// 4-float vectors for any CPU and 8-float AVX2/FMA vectors (see simd.hpp). Each cell's
// position is its centre (eq. 17-18) plus its remainder (eq. 9-10); turned with the frame
// (eq. 11-14) it gives the cell it lands in and the new remainders (eq. 15-16, 5-7), and
// its sums are re-expressed about the new cell's centre and stored there. Private to the
// library.
#pragma once

#include <cstdint>

#include "float8.hpp"
#include "ugv/terrain/cell_sums.hpp"

namespace ugv::terrain::detail {

// Constants of one rotation. The frame turns by the angle (cos c, sin s) about the pivot.
struct TurnConstants
{
    float c_g, s_g, cc, ss;               // cos and sin of the angle over the grid size (1/m); cos^2, sin^2
    float g, minus_half_g;                // grid size (m), and minus half of it
    float nx, ny;                         // rows and columns (a row is ny cells)
    float row_shift_cells;                // eq. 6: physical row = (i + m_i) mod nx; m_i times ny
    int32_t cells;                        // nx * ny
};

// Where the turned cells go: the working map, whose counts are all 0 when the rotation
// starts (its sums are stale and never read). A cell that is the first to land on a
// working cell is stored there whole, with its count (at least 1: a count is how the next
// one sees that the cell is taken); one that lands on a cell already taken is kept in the
// merge list, which the caller merges (add_sums) and empties after each row.
struct TurnTarget
{
    CellSums* sums;
    uint32_t* counts;
    CellSums* merge_sums;  // room for one row
    uint32_t* merge_counts;
    int32_t* merge_to;
    int merges = 0;
    int turned_out = 0;  // non-empty cells turned out of the map
    // Bit j % 8 of byte j / 8 set where cell j of the row holds sums: the kernel writes the
    // row's first (ny + 7) / 8 bytes (of held_row_bytes(ny), turn_end.hpp).
    uint8_t* known_row = nullptr;
};

// One physical row: ny cells (and their sample counts), whose centres turn to
// (row_x + column_x[j], column_y[j] - row_y) in cells (column_* padded with any value to a
// multiple of 8). The row's counts are set to 0 once read: the map being turned is the
// next rotation's working map, whose counts must start at 0, and zeroing them here, where
// they are in the cache, costs less than a pass over the whole map then.
using TurnRow = void (*)(const TurnConstants& t, const CellSums* cells, uint32_t* counts, int ny, float row_x,
                         float row_y, const float* column_x, const float* column_y, TurnTarget& target);

void turn_row_generic(const TurnConstants& t, const CellSums* cells, uint32_t* counts, int ny, float row_x,
                      float row_y, const float* column_x, const float* column_y, TurnTarget& target);
#if defined(UGV_TERRAIN_HAVE_AVX2)
void turn_row_avx2(const TurnConstants& t, const CellSums* cells, uint32_t* counts, int ny, float row_x,
                   float row_y, const float* column_x, const float* column_y, TurnTarget& target);
#endif

// The kernel of the level simd_level() names.
TurnRow turn_row_kernel();

}  // namespace ugv::terrain::detail
