// The end of a rotation (see EgocentricGrid::transform): the working cells nothing landed on
// that still hold the sums of the map turned before are made empty, found from the counts
// (0: nothing landed) and the known bits kept from that turn, without reading the sums. In
// two builds, like turn_row.hpp. Private to the library.
#pragma once

#include <cstdint>

#include "float8.hpp"
#include "ugv/terrain/cell_sums.hpp"

namespace ugv::terrain::detail {

// Bytes a row of a map's known bits (bit j % 8 of byte j / 8 for cell j): whole 32-bit
// words, so that 32 cells' bits are read at once. The bits past a row's last cell are 0.
inline int held_row_bytes(int ny) { return (ny + 31) / 32 * 4; }

// Makes empty each of the nx * ny working cells whose count is 0 and whose bit is set in
// held (held_row_bytes(ny) a row). Counts are read 32 at a time, past a row's end into the
// next row's (their bits are 0), never past the map's end.
using ClearUnlanded = void (*)(CellSums* working, const uint32_t* counts, const uint8_t* held, int nx, int ny);

void clear_unlanded_generic(CellSums* working, const uint32_t* counts, const uint8_t* held, int nx, int ny);
#if defined(UGV_TERRAIN_HAVE_AVX2)
void clear_unlanded_avx2(CellSums* working, const uint32_t* counts, const uint8_t* held, int nx, int ny);
#endif

// The build of the level simd_level() names.
ClearUnlanded clear_unlanded_kernel();

}  // namespace ugv::terrain::detail
