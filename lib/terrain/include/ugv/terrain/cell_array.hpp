// The cells of a grid: their sums (32 bytes each, see cell_sums.hpp) and, in an array of
// their own, their sample counts N (Table 1 #1). The fusion loop touches one sums entry and
// one count per point; a whole-grid pass (rotation, snapshot) reads both arrays in order.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "ugv/terrain/cell_sums.hpp"

namespace ugv::terrain {

class CellArray
{
public:
    explicit CellArray(std::size_t size) : sums_(size), counts_(size, 0) {}

    std::size_t size() const { return sums_.size(); }
    CellSums& sums(int cell) { return sums_[static_cast<std::size_t>(cell)]; }
    const CellSums& sums(int cell) const { return sums_[static_cast<std::size_t>(cell)]; }
    uint32_t count(int cell) const { return counts_[static_cast<std::size_t>(cell)]; }
    uint32_t& count(int cell) { return counts_[static_cast<std::size_t>(cell)]; }
    CellSums* sums_data() { return sums_.data(); }
    uint32_t* counts_data() { return counts_.data(); }

    // One sample into one cell (see fuse_sample).
    void fuse(int cell, float x_rel_m, float y_rel_m, double z_m, float w)
    {
        fuse_sample(sums_[static_cast<std::size_t>(cell)], x_rel_m, y_rel_m, z_m, w);
        ++counts_[static_cast<std::size_t>(cell)];
    }
    // Merges sums that hold n samples into a cell.
    void add(int cell, const CellSums& s, uint32_t n)
    {
        add_sums(sums_[static_cast<std::size_t>(cell)], s);
        counts_[static_cast<std::size_t>(cell)] += n;
    }
    // Empties count cells from first on.
    void clear(std::size_t first, std::size_t count);
    void clear() { clear(0, size()); }
    void swap(CellArray& other)
    {
        sums_.swap(other.sums_);
        counts_.swap(other.counts_);
    }

private:
    std::vector<CellSums> sums_;
    std::vector<uint32_t> counts_;
};

}  // namespace ugv::terrain
