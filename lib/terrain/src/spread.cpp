#include "ugv/terrain/spread.hpp"

#include <algorithm>
#include <cmath>

namespace ugv::terrain {

AxisFootprint axis_footprint(float centre_cells, float half_width_cells, int limit)
{
    AxisFootprint f;
    const float h = std::clamp(half_width_cells, 1e-6f, static_cast<float>(kMaxSpreadCells));
    const float lo = std::max(centre_cells - h, 0.0f);
    const float hi = std::min(centre_cells + h, static_cast<float>(limit));
    if (!(hi > lo)) return f;
    const int first = static_cast<int>(std::floor(lo));
    const int last = std::min(static_cast<int>(std::ceil(hi)) - 1, limit - 1);
    float total = 0.0f;
    for (int k = first; k <= last && f.count < 2 * kMaxSpreadCells + 2; ++k) {
        const float a = std::max(lo, static_cast<float>(k));
        const float b = std::min(hi, static_cast<float>(k + 1));
        if (!(b > a)) continue;
        if (f.count == 0) f.first = k;
        // Cells are contiguous: a gap cannot occur inside [lo, hi].
        f.fraction[f.count] = b - a;
        f.centre[f.count] = 0.5f * (a + b) - (static_cast<float>(k) + 0.5f);
        total += b - a;
        ++f.count;
    }
    for (int k = 0; k < f.count; ++k) f.fraction[k] /= total;
    return f;
}

}  // namespace ugv::terrain
