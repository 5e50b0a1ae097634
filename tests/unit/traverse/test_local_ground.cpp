// The classifier's local ground (separable moment sums, outliers subtracted, a selection by
// counting) against local_ground_reference, the plain lattice-point-by-lattice-point
// version, on random and structured maps, several radii and map sizes.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "traverse_maps.hpp"
#include "ugv_test/terrain_grid_builder.hpp"
#include "ugv/traverse/cell_classifier.hpp"

using namespace ugv::traverse;
using namespace ugv::traverse::test;

namespace {

struct Comparison
{
    int cells = 0, known = 0, equal = 0;
    double worst = 0;  // largest |fast - reference|, m
};

Comparison compare(const TerrainGrid& g, const ClassifierConfig& config)
{
    CellClassifier classifier{config};
    TraversabilityLayers layers;
    classifier.classify(g, Odometer{}, layers);
    std::vector<uint8_t> known(g.cells());
    for (std::size_t k = 0; k < g.cells(); ++k) known[k] = layers.cell_class[k] != CellClass::unknown ? 1 : 0;
    std::vector<float> reference;
    local_ground_reference(ground_levels(g, known, config.min_support_samples), known,
                           ground_points(g, known, config.min_support_samples, config.max_step_m),
                           config.ground_radius_m, config.max_step_m, reference);
    Comparison c;
    REQUIRE(reference.size() == layers.ground_m.size());
    for (std::size_t k = 0; k < g.cells(); ++k) {
        ++c.cells;
        const float f = layers.ground_m[k], r = reference[k];
        INFO("cell " << k / g.ny << ", " << k % g.ny);
        REQUIRE(std::isnan(f) == std::isnan(r));
        if (std::isnan(r)) continue;
        ++c.known;
        c.equal += f == r ? 1 : 0;
        c.worst = std::max(c.worst, static_cast<double>(std::abs(f - r)));
    }
    return c;
}

}  // namespace

TEST_CASE("the fast local ground equals the plain one on random maps")
{
    const bool avx2 = GENERATE(true, false);
    CAPTURE(avx2);
    const Avx2Allowed allowed(avx2);
    std::mt19937 rng(20261202);
    int maps = 0;
    Comparison all;
    for (const double base : {0.0, 1.5, -3.0, 750.0, 2400.0})
        for (const double radius : {1.5, 0.5, 0.9, 2.5})
            for (const auto& [nx, ny] : {std::pair{150, 150}, std::pair{37, 61}, std::pair{9, 5}}) {
                CAPTURE(base, radius, nx, ny);
                ClassifierConfig config;
                config.ground_radius_m = radius;
                config.max_step_m = radius > 2 ? 0.3 : 0.2;
                const Comparison c = compare(random_map(rng, nx, ny, base), config);
                // The sums are the same floats times integer offsets, exact in double in
                // any order: the same planes, the same levels, the same floats.
                CHECK(c.worst == 0.0);
                all.cells += c.cells;
                all.known += c.known;
                all.equal += c.equal;
                ++maps;
            }
    CHECK(maps == 60);
    CHECK(all.known > 200'000);
    CHECK(all.equal == all.known);
}

TEST_CASE("the fast local ground equals the plain one on the known-answer shapes")
{
    const bool avx2 = GENERATE(true, false);
    CAPTURE(avx2);
    const Avx2Allowed allowed(avx2);
    // Flat, a box, a wall, a ditch, a 35-degree ramp, each with the ground at 1.5 m.
    const std::vector<std::function<double(double, double)>> shapes = {
        [](double, double) { return 1.5; },
        [](double x, double y) { return 1.5 + (x >= 8.0 && x < 8.6 && y >= -0.3 && y < 0.3 ? 0.5 : 0.0); },
        [](double x, double y) { return 1.5 + (y > 7 && y < 7.3 && x > 4 && x < 25 ? 3.0 : 0.0); },
        [](double x, double) { return 1.5 - (x >= 10.0 && x < 11.0 ? 0.4 : 0.0); },
        [](double x, double) { return 1.5 + (x > 5 ? (x - 5) * std::tan(35.0 * M_PI / 180.0) : 0.0); },
    };
    for (std::size_t s = 0; s < shapes.size(); ++s) {
        CAPTURE(s);
        TerrainGrid g = empty_grid();
        fill(g, shapes[s]);
        const Comparison c = compare(g, ClassifierConfig{});
        CHECK(c.known == static_cast<int>(g.cells()));
        CHECK(c.equal == c.known);
    }
}
