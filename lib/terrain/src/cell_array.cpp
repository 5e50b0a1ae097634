#include "ugv/terrain/cell_array.hpp"

#include <algorithm>

namespace ugv::terrain {

void CellArray::clear(std::size_t first, std::size_t count)
{
    const auto from = static_cast<std::ptrdiff_t>(first);
    const auto to = static_cast<std::ptrdiff_t>(first + count);
    std::fill(sums_.begin() + from, sums_.begin() + to, CellSums{});
    std::fill(tallies_.begin() + from, tallies_.begin() + to, CellTally{});
}

}  // namespace ugv::terrain
