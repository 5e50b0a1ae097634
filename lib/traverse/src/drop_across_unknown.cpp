#include "drop_across_unknown.hpp"

#include "local_ground.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace ugv::traverse {

DropsAcrossUnknown::DropsAcrossUnknown(double radius_m, double resolution_m)
    : radius_m_(radius_m), resolution_m_(resolution_m)
{
    const int h = ground_half_width(radius_m, resolution_m);  // as the classifier's window of tops
    for (int di = -h; di <= h; ++di)
        for (int dj = -h; dj <= h; ++dj) {
            const double d = std::hypot(di, dj) * resolution_m;
            if (std::max(std::abs(di), std::abs(dj)) < 2 || d > radius_m + 1e-6) continue;
            Offset o{di, dj, d, {}};
            // Points along the segment, off the cells' boundaries by half a step.
            constexpr int kSteps = 64;
            for (int s = 0; s < kSteps; ++s) {
                const double t = (s + 0.5) / kSteps;
                const int p = static_cast<int>(std::lround(t * di)), q = static_cast<int>(std::lround(t * dj));
                if ((p == 0 && q == 0) || (p == di && q == dj)) continue;
                if (std::find(o.between.begin(), o.between.end(), std::make_pair(p, q)) == o.between.end())
                    o.between.emplace_back(p, q);
            }
            const auto [p, q] = o.between.front();
            around_[static_cast<std::size_t>((p + 1) * 3 + q + 1)].push_back(std::move(o));
        }
    for (auto& group : around_)
        std::sort(group.begin(), group.end(), [](const Offset& a, const Offset& b) { return a.distance_m < b.distance_m; });
}

void DropsAcrossUnknown::mark(const TerrainGrid& g, const std::vector<float>& top, const std::vector<float>& bottom,
                              const std::vector<float>& lowest_top, double max_drop_m, double max_slope_deg, uint8_t bit,
                              uint8_t skip, std::vector<uint8_t>& flags, std::vector<float>& drop_m) const
{
    const int nx = g.nx, ny = g.ny;
    const double tan_slope = std::tan(max_slope_deg * M_PI / 180.0);
    auto at = [ny](int i, int j) { return static_cast<std::size_t>(i) * ny + j; };
    auto inside = [nx, ny](int i, int j) { return i >= 0 && j >= 0 && i < nx && j < ny; };
    auto known = [&](int i, int j) { return !std::isnan(top[at(i, j)]); };
    for (int i = 0; i < nx; ++i)
        for (int j = 0; j < ny; ++j) {
            const std::size_t k = at(i, j);
            if (!known(i, j) || (flags[k] & skip) || !(static_cast<double>(bottom[k]) - lowest_top[k] >= max_drop_m))
                continue;
            float found = 0.0f;
            // Only the segments that leave the cell through an unknown neighbour.
            for (int p = -1; p <= 1; ++p)
                for (int q = -1; q <= 1; ++q) {
                    if ((p == 0 && q == 0) || !inside(i + p, j + q) || known(i + p, j + q)) continue;
                    for (const Offset& o : around_[static_cast<std::size_t>((p + 1) * 3 + q + 1)]) {
                        const int ti = i + o.di, tj = j + o.dj;
                        if (!inside(ti, tj) || !known(ti, tj)) continue;
                        const double drop = static_cast<double>(bottom[k]) - top[at(ti, tj)];
                        if (drop < max_drop_m || drop < tan_slope * o.distance_m) continue;
                        bool unseen = true;
                        for (const auto& [bi, bj] : o.between)
                            if (!inside(i + bi, j + bj) || known(i + bi, j + bj)) {
                                unseen = false;
                                break;
                            }
                        if (unseen) found = std::max(found, static_cast<float>(drop));
                    }
                }
            if (found > 0.0f) {
                flags[k] |= bit;
                drop_m[k] = std::isnan(drop_m[k]) ? found : std::max(drop_m[k], found);
            }
        }
}

}  // namespace ugv::traverse
