// The highest and lowest height (z, ENU) of the samples that fell in a cell: what a mean
// hides, e.g. how tall a wall is whose cell also holds the ground in front of it. Kept per
// slot beside the sums (cell_array.hpp), so the rotation moves them with the slot, and
// merged like them when cells land together.
#pragma once

#include <limits>

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

}  // namespace ugv::terrain
