// The one table of the terrain library's vector kernels: the fusion's placement of points and
// the egocentric map's rotation, each in a generic build (4-float vectors) and an AVX2/FMA
// build (8-float vectors). The table is chosen once, at start-up, from the CPU's feature bits;
// set_simd_level (simd.hpp) swaps it for tests and benchmarks. The map calls its kernels only
// through this table, so a call site never chooses a build. Private to the library.
#pragma once

#include "fusion_kernels.hpp"
#include "spread_corners.hpp"
#include "turn_slots.hpp"
#include "ugv/terrain/simd.hpp"

namespace ugv::terrain::detail {

struct KernelTable
{
    SimdLevel level;
    PlaceChunk place_chunk;  // rows and columns rings (eq. 6)
    TurnSlots turn_slots;
    FindMerges find_merges;
    SpreadCorners spread_corners;           // a spread point's summed-area corners
    SpreadCorners spread_corners_centred;   // the same, centred form (4 components)
};

// The table in use.
const KernelTable& kernels();
// The table of a level (tests compare each with the reference; only call the kernels of a
// level the CPU runs, best_simd_level()).
const KernelTable& kernel_table(SimdLevel level);

}  // namespace ugv::terrain::detail
