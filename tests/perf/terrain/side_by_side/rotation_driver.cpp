// One version's half of the side-by-side rotation timing (rotation.sh). Compiled once per
// version with -Dugv=ugvA or -Dugv=ugvB, together with that version's lib/terrain, so that
// two versions of the library live in one process under different namespaces.
#include <chrono>
#include <cmath>

#include "ugv/terrain/egocentric_grid.hpp"

namespace ugv::side_by_side {

using terrain::EgocentricGrid;

namespace {
EgocentricGrid* original = nullptr;  // the map every call starts from
EgocentricGrid* turned = nullptr;    // a copy of it, turned once per call
}  // namespace

// An n x n map of 0.2 m cells, each known cell holding two samples off its centre; with
// known_radius_m > 0 only the cells within that distance of the rear edge's centre.
void make_map(int n, double known_radius_m)
{
    original = new EgocentricGrid(n, n, 0.2);
    const double y_min = -0.1 * n;
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            const double x = (i + 0.5) * 0.2, y = y_min + (j + 0.5) * 0.2;
            if (known_radius_m > 0.0 && std::hypot(x, y) > known_radius_m) continue;
            float x_rel = 0.0f, y_rel = 0.0f;
            const int cell = original->locate(static_cast<float>((i + 0.3) * 0.2),
                                              static_cast<float>(y_min + (j + 0.6) * 0.2), x_rel, y_rel);
            original->fuse(cell, x_rel, y_rel, 0.01 * i, 100.0f);
            original->fuse(cell, x_rel * 0.5f, y_rel, 0.01 * j, 50.0f);
        }
    }
    turned = new EgocentricGrid(*original);
}

// Microseconds of one 5 deg rotation about (0.1, 0) of a fresh copy of the map.
double time_rotation()
{
    *turned = *original;
    const auto start = std::chrono::steady_clock::now();
    volatile int dropped = turned->transform(5.0 * M_PI / 180.0, 0.1, 0.0);
    const auto end = std::chrono::steady_clock::now();
    (void)dropped;
    return std::chrono::duration<double, std::micro>(end - start).count();
}

// A sum over the turned map's known cells, to see that both versions turned the same map.
double checksum()
{
    double sum = 0.0;
    for (int c = 0; c < turned->nx() * turned->ny(); ++c)
        if (!turned->at(c).empty()) sum += turned->at(c).w + turned->at(c).x_wx + turned->at(c).x_wx2 + turned->count(c);
    return sum;
}

}  // namespace ugv::side_by_side
