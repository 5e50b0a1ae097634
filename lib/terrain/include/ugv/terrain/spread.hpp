// Section 3.5: a point whose horizontal sigma exceeds the grid size is fused into every
// cell its footprint overlaps. The footprint is the square of half-width sigma (capped)
// around the point; each cell gets the fraction of the footprint's area that falls on it,
// so the point's total weight is conserved.
#pragma once

#include "ugv/terrain/map_config.hpp"

namespace ugv::terrain {

// The overlap of [centre - half_width, centre + half_width] with unit cells [k, k + 1),
// in cell units, restricted to cells [0, limit).
struct AxisFootprint
{
    int first = 0;   // first cell index
    int count = 0;   // cells overlapped
    float fraction[2 * kMaxSpreadCells + 2] = {};  // share of the footprint in each (sums to 1)
    float centre[2 * kMaxSpreadCells + 2] = {};    // centre of the overlap in each, from the cell centre (cells)
};

// Fractions are renormalised over the cells inside [0, limit) so that they sum to 1; count
// is 0 when nothing overlaps. half_width_cells is clamped to kMaxSpreadCells.
AxisFootprint axis_footprint(float centre_cells, float half_width_cells, int limit);

}  // namespace ugv::terrain
