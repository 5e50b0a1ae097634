// The top of a drop whose face the laser cannot see (docs/traverse.md, section 1, step 4).
#pragma once

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "ugv/traverse/terrain_grid.hpp"

namespace ugv::traverse {

// The near wall of a ditch or a drop-off lies in its rim's shadow: the rim and the floor are
// known, the cells between them unknown, and they lie farther apart than the step windows
// look. For each known cell (top and bottom not NaN) without the `skip` bit, the known cells
// within radius_m (2 cells or more away) seen across unknown cells only: where the cell's
// bottom stands max_drop_m or more above such a cell's top, and more steeply than
// max_slope_deg over the distance between their centres (the gentlest surface the data
// allows between them), the cell is the top of a drop: mark() sets `bit` in its flags and
// raises its drop_m (NaN counts as 0) to that drop.
class DropsAcrossUnknown
{
public:
    // The offsets within radius_m, for one resolution (built once: the classifier keeps it).
    DropsAcrossUnknown(double radius_m, double resolution_m);
    bool built_for(double radius_m, double resolution_m) const
    {
        return radius_m == radius_m_ && resolution_m == resolution_m_;
    }
    // lowest_top: the least top (+inf where none) in each cell's square of half-width
    // radius_m, which rules out most cells at once.
    void mark(const TerrainGrid& grid, const std::vector<float>& top, const std::vector<float>& bottom,
              const std::vector<float>& lowest_top, double max_drop_m, double max_slope_deg, uint8_t bit, uint8_t skip,
              std::vector<uint8_t>& flags, std::vector<float>& drop_m) const;

private:
    struct Offset
    {
        int di, dj;
        double distance_m;
        std::vector<std::pair<int, int>> between;  // the cells the segment to it crosses, nearest first
    };
    double radius_m_, resolution_m_;
    // Grouped by the neighbour the segment leaves through (index (p + 1) * 3 + q + 1),
    // nearest first in each group.
    std::array<std::vector<Offset>, 9> around_;
};

}  // namespace ugv::traverse
