// The fusion loop's last step, on the map's side: one placed sample into a cell's sums (as
// two vector adds), its count, its extremes and its newest time. What the placement kernels computed
// (kernels/fusion_kernels.hpp) ends here; a new per-cell quantity goes into CellTally
// (cell_tally.hpp). Private to the library.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

#include "kernels/float4.hpp"
#include "ugv/terrain/cell_array.hpp"

namespace ugv::terrain::detail {

// The cell's layout as two vectors: {w, x_wx, y_wy, z_wz} and {z_ref_m, x_wx2, y_wy2, z_wz2}.
static_assert(offsetof(CellSums, x_wx) == 4 && offsetof(CellSums, y_wy) == 8 && offsetof(CellSums, z_wz) == 12);
static_assert(offsetof(CellSums, z_ref_m) == 16 && offsetof(CellSums, x_wx2) == 20 &&
              offsetof(CellSums, y_wy2) == 24 && offsetof(CellSums, z_wz2) == 28);

// sample = {0, x_rel_m, y_rel_m, z_m}: exactly what fuse_sample does. The reference check
// comes first, on scalars, so that no vector is live across the (rare) call.
inline void fuse_point_into(CellSums& cell, const float* sample, float w)
{
    if (!(w <= cell.w)) move_reference(cell, sample[3]);  // empty (w is NaN), or w outweighs the cell: see fuse_sample
    Float4 sums, squares;
    std::memcpy(&sums, &cell.w, sizeof sums);
    std::memcpy(&squares, &cell.z_ref_m, sizeof squares);
    const Float4 reference = __builtin_shufflevector(squares, Float4{}, 4, 4, 4, 0);  // {0, 0, 0, z_ref}
    const Float4 d = load4(sample) - reference;  // {0, x, y, dz}, loaded after the call: nothing vector is live across it
    const Float4 weighted = (d + Float4{1.0f, 0.0f, 0.0f, 0.0f}) * w;                 // {w, wx, wy, w dz}
    sums += weighted;
    squares += weighted * d;  // {+0: z_ref stays, w x^2, w y^2, w dz^2}
    std::memcpy(&cell.w, &sums, sizeof sums);
    std::memcpy(&cell.z_ref_m, &squares, sizeof squares);
}

// The arrays of a CellArray, taken once per batch.
struct CellArrays
{
    CellSums* sums;
    CellTally* tallies;

    explicit CellArrays(CellArray& a) : sums(a.sums_data()), tallies(a.tallies_data()) {}

    void add_placed(uint32_t at, const float* sample, float w, TimeTick t_ms) const
    {
        const float z = sample[3];
        fuse_point_into(sums[at], sample, w);
        tallies[at].add(z, t_ms);
    }
};

}  // namespace ugv::terrain::detail
