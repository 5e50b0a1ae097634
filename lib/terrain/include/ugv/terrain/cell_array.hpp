// The cells of a grid: their sums (32 bytes each, see cell_sums.hpp) and, in an array of
// its own indexed the same way, their other quantities (CellTally, cell_tally.hpp: the
// sample count N, Table 1 #1, the extremes of z and the newest sample's time). The fusion loop touches one entry of
// each per point; a whole-grid pass (snapshot) reads them in order. The vector kernels see
// only the sums (the rotation moves slots, not the cells' contents), so a quantity added to
// CellTally changes neither them nor this class.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "ugv/terrain/cell_tally.hpp"
#include "ugv/terrain/cell_sums.hpp"

namespace ugv::terrain {

class CellArray
{
public:
    explicit CellArray(std::size_t size) : sums_(size), tallies_(size) {}

    std::size_t size() const { return sums_.size(); }
    CellSums& sums(int cell) { return sums_[static_cast<std::size_t>(cell)]; }
    const CellSums& sums(int cell) const { return sums_[static_cast<std::size_t>(cell)]; }
    const CellTally& tally(int cell) const { return tallies_[static_cast<std::size_t>(cell)]; }
    CellTally& tally(int cell) { return tallies_[static_cast<std::size_t>(cell)]; }
    uint32_t count(int cell) const { return tally(cell).count; }
    CellSums* sums_data() { return sums_.data(); }
    CellTally* tallies_data() { return tallies_.data(); }

    // One sample, taken at t_ms, into one cell (see fuse_sample).
    void fuse(int cell, float x_rel_m, float y_rel_m, double z_m, float w, TimeTick t_ms)
    {
        const auto k = static_cast<std::size_t>(cell);
        fuse_sample(sums_[k], x_rel_m, y_rel_m, z_m, w);
        tallies_[k].add(static_cast<float>(z_m), t_ms);
    }
    // Cell from's samples added into cell into (cells that land together in a rotation);
    // from is left as it was.
    void merge(int into, int from)
    {
        const auto a = static_cast<std::size_t>(into), b = static_cast<std::size_t>(from);
        add_sums(sums_[a], sums_[b]);
        tallies_[a].merge(tallies_[b]);
    }
    // Cell from's content into cell to (the pool's compaction); from is left as it was.
    void move(int to, int from)
    {
        const auto a = static_cast<std::size_t>(to), b = static_cast<std::size_t>(from);
        sums_[a] = sums_[b];
        tallies_[a] = tallies_[b];
    }
    // Empties one cell.
    void reset(int cell)
    {
        const auto k = static_cast<std::size_t>(cell);
        sums_[k] = CellSums{};
        tallies_[k] = CellTally{};
    }
    // Empties count cells from first on.
    void clear(std::size_t first, std::size_t count);
    void clear() { clear(0, size()); }

private:
    std::vector<CellSums> sums_;
    std::vector<CellTally> tallies_;
};

}  // namespace ugv::terrain
