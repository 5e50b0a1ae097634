// A cell's quantities other than its sums (CellTally): its sample count, the highest and
// lowest height (z, ENU) of its samples (CellExtremes: what a mean hides, e.g. how tall a
// wall is whose cell also holds the ground in front of it) and the time of its newest
// sample (how old what the cell says is). Kept per slot beside the sums
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

// A sample's time as the tallies keep it: whole milliseconds since an epoch the mapper
// keeps (TerrainMapper: its first pose, moved on before the count could overflow).
using TimeTick = int32_t;
// No sample: older than any tick, so that the newest of it and a tick is the tick.
constexpr TimeTick kNoTime = std::numeric_limits<TimeTick>::min();

// 16 bytes (four to a cache line): the count, the extremes and the newest time share the
// line the fusion loop touches beside the cell's sums.
struct CellTally
{
    uint32_t count = 0;  // Table 1 #1: N
    CellExtremes extremes;
    TimeTick newest_ms = kNoTime;  // the newest sample's time

    void add(float z_m, TimeTick t_ms)
    {
        ++count;
        extremes.add(z_m);
        newest_ms = newest_ms > t_ms ? newest_ms : t_ms;
    }
    void merge(const CellTally& o)
    {
        count += o.count;
        extremes.merge(o.extremes);
        newest_ms = newest_ms > o.newest_ms ? newest_ms : o.newest_ms;
    }
};
static_assert(sizeof(CellTally) == 16);

// The tallies as a map snapshot publishes them: one array per quantity, cell (i, j) at
// i * ny + j; an unknown cell has count 0 and NaN heights and age.
struct TallyLayers
{
    std::vector<int32_t> count;
    std::vector<float> max_z_m;  // highest sample of the cell
    std::vector<float> min_z_m;  // lowest sample of the cell
    std::vector<float> age_s;    // the snapshot's time minus the newest sample's

    void reset(std::size_t cells)
    {
        constexpr float nan = std::numeric_limits<float>::quiet_NaN();
        count.assign(cells, 0);
        max_z_m.assign(cells, nan);
        min_z_m.assign(cells, nan);
        age_s.assign(cells, nan);
    }
    // now_ms: the snapshot's time on the tallies' clock (TimeTick, with its fraction).
    void put(std::size_t k, const CellTally& t, double now_ms)
    {
        count[k] = static_cast<int32_t>(std::min<uint32_t>(t.count, 0x7fffffff));
        max_z_m[k] = t.extremes.z_max_m;
        min_z_m[k] = t.extremes.z_min_m;
        age_s[k] = t.newest_ms == kNoTime ? std::numeric_limits<float>::quiet_NaN()
                                          : static_cast<float>((now_ms - t.newest_ms) * 1e-3);
    }
};

}  // namespace ugv::terrain
