// The cells of a grid: their sums (32 bytes each, see cell_sums.hpp) and, in arrays of
// their own indexed the same way, the other per-cell quantities: the sample count N (Table
// 1 #1) and the extremes of z (cell_extremes.hpp). The fusion loop touches one entry of each
// per point; a whole-grid pass (snapshot) reads them in order.
//
// A per-cell quantity beside the sums is added here: an array, and its part in fuse, merge,
// move, reset and clear (and in the fusion loop's add_placed, src/cell_fusion.hpp). The
// vector kernels see only the sums (the rotation moves slots, not the cells' contents), so
// they do not change.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "ugv/terrain/cell_extremes.hpp"
#include "ugv/terrain/cell_sums.hpp"

namespace ugv::terrain {

class CellArray
{
public:
    explicit CellArray(std::size_t size) : sums_(size), counts_(size, 0), extremes_(size) {}

    std::size_t size() const { return sums_.size(); }
    CellSums& sums(int cell) { return sums_[static_cast<std::size_t>(cell)]; }
    const CellSums& sums(int cell) const { return sums_[static_cast<std::size_t>(cell)]; }
    uint32_t count(int cell) const { return counts_[static_cast<std::size_t>(cell)]; }
    uint32_t& count(int cell) { return counts_[static_cast<std::size_t>(cell)]; }
    const CellExtremes& extremes(int cell) const { return extremes_[static_cast<std::size_t>(cell)]; }
    CellExtremes& extremes(int cell) { return extremes_[static_cast<std::size_t>(cell)]; }
    CellSums* sums_data() { return sums_.data(); }
    uint32_t* counts_data() { return counts_.data(); }
    CellExtremes* extremes_data() { return extremes_.data(); }

    // One sample into one cell (see fuse_sample).
    void fuse(int cell, float x_rel_m, float y_rel_m, double z_m, float w)
    {
        const auto k = static_cast<std::size_t>(cell);
        fuse_sample(sums_[k], x_rel_m, y_rel_m, z_m, w);
        ++counts_[k];
        extremes_[k].add(static_cast<float>(z_m));
    }
    // Cell from's samples added into cell into (cells that land together in a rotation);
    // from is left as it was.
    void merge(int into, int from)
    {
        const auto a = static_cast<std::size_t>(into), b = static_cast<std::size_t>(from);
        add_sums(sums_[a], sums_[b]);
        counts_[a] += counts_[b];
        extremes_[a].merge(extremes_[b]);
    }
    // Cell from's content into cell to (the pool's compaction); from is left as it was.
    void move(int to, int from)
    {
        const auto a = static_cast<std::size_t>(to), b = static_cast<std::size_t>(from);
        sums_[a] = sums_[b];
        counts_[a] = counts_[b];
        extremes_[a] = extremes_[b];
    }
    // Empties one cell.
    void reset(int cell)
    {
        const auto k = static_cast<std::size_t>(cell);
        sums_[k] = CellSums{};
        counts_[k] = 0;
        extremes_[k] = CellExtremes{};
    }
    // Empties count cells from first on.
    void clear(std::size_t first, std::size_t count);
    void clear() { clear(0, size()); }

private:
    std::vector<CellSums> sums_;
    std::vector<uint32_t> counts_;
    std::vector<CellExtremes> extremes_;
};

}  // namespace ugv::terrain
