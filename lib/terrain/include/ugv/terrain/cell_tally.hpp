// A cell's quantities other than its sums (CellTally): its sample count and the highest and
// lowest height (z, ENU) of its samples (CellExtremes: what a mean hides, e.g. how tall a
// wall is whose cell also holds the ground in front of it). Kept per slot beside the sums
// (cell_array.hpp), so the rotation moves them with the slot, and merged like them when
// cells land together. A new per-cell quantity is a field of CellTally, a line in its add
// and merge, and its array in TallyLayers; the vector kernels, which see only the sums, and
// the map's snapshot code, which copies whole tallies, do not change.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

namespace ugv::terrain {

struct CellExtremes
{
    float z_max_m = std::numeric_limits<float>::quiet_NaN();  // NaN: no sample
    float z_min_m = std::numeric_limits<float>::quiet_NaN();

    // One sample of height z (finite). Written so that an empty cell's NaN gives way
    // (a > b ? a : b is false for NaN) and the compiler emits one max and one min.
    void add(float z_m)
    {
        z_max_m = z_max_m > z_m ? z_max_m : z_m;
        z_min_m = z_min_m < z_m ? z_min_m : z_m;
    }
    // Another cell's samples (cells merged in a rotation): max of maxes, min of mins; an
    // empty side changes nothing.
    void merge(const CellExtremes& o)
    {
        if (o.z_max_m > z_max_m || z_max_m != z_max_m) z_max_m = o.z_max_m;
        if (o.z_min_m < z_min_m || z_min_m != z_min_m) z_min_m = o.z_min_m;
    }
};

// 12 bytes: the count and the extremes share the cache line the fusion loop touches beside
// the cell's sums.
struct CellTally
{
    uint32_t count = 0;  // Table 1 #1: N
    CellExtremes extremes;

    void add(float z_m)
    {
        ++count;
        extremes.add(z_m);
    }
    void merge(const CellTally& o)
    {
        count += o.count;
        extremes.merge(o.extremes);
    }
};

// The tallies as a map snapshot publishes them: one array per quantity, cell (i, j) at
// i * ny + j; an unknown cell has count 0 and NaN heights.
struct TallyLayers
{
    std::vector<int32_t> count;
    std::vector<float> max_z_m;  // highest sample of the cell
    std::vector<float> min_z_m;  // lowest sample of the cell

    void reset(std::size_t cells)
    {
        constexpr float nan = std::numeric_limits<float>::quiet_NaN();
        count.assign(cells, 0);
        max_z_m.assign(cells, nan);
        min_z_m.assign(cells, nan);
    }
    void put(std::size_t k, const CellTally& t)
    {
        count[k] = static_cast<int32_t>(std::min<uint32_t>(t.count, 0x7fffffff));
        max_z_m[k] = t.extremes.z_max_m;
        min_z_m[k] = t.extremes.z_min_m;
    }
};

}  // namespace ugv::terrain
