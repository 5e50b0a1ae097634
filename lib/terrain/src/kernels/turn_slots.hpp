// The egocentric map's rotation (eq. 9-16) on its pool of known cells, in two builds of
// the same steps: 4-float vectors for any CPU and 8-float AVX2/FMA vectors (kernel_table.hpp).
// Each cell's position is its centre (eq. 17-18) plus its remainder (eq. 9-10); turned with
// the frame (eq. 11-14) it gives the cell it lands in and the new remainders (eq. 15-16,
// 5-7). Its sums are re-expressed about the new cell's centre where they are, in the pool,
// and its slot goes into the working index grid. Private to the library.
#pragma once

#include <cstdint>

#include "float8.hpp"
#include "ugv/terrain/cell_sums.hpp"

namespace ugv::terrain::detail {

// An index grid's entry for a cell without sums.
constexpr uint32_t kNoSlot = 0xffffffffu;

// Constants of one rotation. The frame turns by the angle (cos c, sin s) about the pivot. A
// cell of row i (unwrapped) and column j whose remainder is (x_re, y_re) lands at row and
// column (in cells, before the floor)
//   f_x = (c x_re + s y_re) / g + c i + s j + offset_x,
//   f_y = (c y_re - s x_re) / g + c j - s i + offset_y.
struct TurnConstants
{
    float c, s;                   // cos and sin of the angle
    float c_g, s_g, cc, ss;       // the same over the grid size (1/m); cos^2, sin^2
    float g, minus_half_g;        // grid size (m), and minus half of it
    float nx, ny, inv_ny;         // rows and columns (a row is ny cells), 1/ny
    float ring_rows;              // eq. 6: physical row = (i + m_i) mod nx; m_i
    float row_shift_cells;        // m_i times ny
    float column_shift;           // m_j: physical column = (j + m_j) mod ny before the turn; 0 after
    float offset_x, offset_y;     // see above (cells)
    int32_t cells;                // nx * ny
};

// Where the turned cells go. slot is the working index grid, every entry kNoSlot (all bits
// set) when the rotation starts: each cell landing in the map writes its slot there, the
// last to land on a cell overwriting the others (find_merges then finds those), and sets
// its bit in placed (bit s % 8 of byte s / 8). A cell turned out of the map has its slot
// emptied (CellSums{}) and listed in dropped (room for every slot).
struct TurnTarget
{
    uint32_t* slot;
    uint8_t* placed;
    uint32_t* dropped;
    int drops = 0;
};

// Turns the slots 0 .. slots - 1 of the pool: sums[s] is re-expressed about its new cell's
// centre (or emptied, if it turned out of the map), home[s] becomes that cell (a physical
// index; any value if the slot was dropped or empty).
// Slots from `slots` up to the next multiple of 8 are read and written too: they must exist
// and be empty (their sums are then not those of CellSums{}, but any empty slot's are reset
// when it is taken).
using TurnSlots = void (*)(const TurnConstants& t, CellSums* sums, uint32_t* home, uint32_t slots,
                           TurnTarget& target);

void turn_slots_generic(const TurnConstants& t, CellSums* sums, uint32_t* home, uint32_t slots, TurnTarget& target);
#if defined(UGV_TERRAIN_HAVE_AVX2)
void turn_slots_avx2(const TurnConstants& t, CellSums* sums, uint32_t* home, uint32_t slots, TurnTarget& target);
#endif

// After turn_slots: the slots placed whose working cell holds another slot (cells that landed
// together; ~1 % of a full map's at 5 deg), listed with that slot (merge_from[m] lands on
// the cell whose slot is merge_into[m]), in increasing order of merge_from. Returns how many.
using FindMerges = int (*)(const uint32_t* working_slot, const uint32_t* home, const uint8_t* placed, uint32_t slots,
                           uint32_t* merge_from, uint32_t* merge_into);

int find_merges_generic(const uint32_t* working_slot, const uint32_t* home, const uint8_t* placed, uint32_t slots,
                        uint32_t* merge_from, uint32_t* merge_into);
#if defined(UGV_TERRAIN_HAVE_AVX2)
int find_merges_avx2(const uint32_t* working_slot, const uint32_t* home, const uint8_t* placed, uint32_t slots,
                     uint32_t* merge_from, uint32_t* merge_into);
#endif

}  // namespace ugv::terrain::detail
