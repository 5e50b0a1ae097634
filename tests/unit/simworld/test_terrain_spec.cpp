#include <catch2/catch.hpp>

#include <cmath>

#include "ugv/simworld/terrain_spec.hpp"

using namespace ugv::simworld;

TEST_CASE("primitives rasterise where they are, at their heights")
{
    TerrainSpec s;
    s.ground_z_m = 1.0;
    s.boxes.push_back({{2.0, 2.0, 3.0, 3.0}, 0.6});
    s.walls.push_back({0.0, 8.0, 10.0, 8.0, 0.4, 3.0});
    s.ramps.push_back({{5.0, 0.0, 9.0, 1.0}, 0.4, Direction::east});
    s.ditches.push_back({{0.0, 4.0, 1.0, 5.0}, 0.3});
    const HeightField f = rasterize(s, {0.0, 0.0, 10.0, 10.0}, 0.1);
    CHECK(f.nx == 100);
    CHECK(f.ny == 100);
    CHECK(f.height_at(2.5, 2.5) == Approx(1.6));
    CHECK(f.height_at(3.05, 2.5) == Approx(1.0));
    CHECK(f.height_at(5.0, 8.1) == Approx(4.0));
    CHECK(f.height_at(5.0, 8.35) == Approx(1.0));  // outside the 0.4 m thickness
    CHECK(f.height_at(5.05, 0.5) == Approx(1.0 + 0.4 * 0.05 / 4.0));
    CHECK(f.height_at(8.95, 0.5) == Approx(1.0 + 0.4 * 3.95 / 4.0));
    CHECK(f.height_at(0.5, 4.5) == Approx(0.7));
}

TEST_CASE("roughness is bounded, smooth, and the same for the same seed")
{
    TerrainSpec s;
    s.roughness_m = 0.05;
    s.roughness_wavelength_m = 2.0;
    s.seed = 3;
    double lo = 1, hi = -1, max_step = 0;
    double prev = roughness_at(s, 0, 1.3);
    for (double x = 0.01; x < 40; x += 0.01) {
        const double z = roughness_at(s, x, 1.3);
        lo = std::min(lo, z);
        hi = std::max(hi, z);
        max_step = std::max(max_step, std::abs(z - prev));
        prev = z;
    }
    CHECK(lo >= -0.05);
    CHECK(hi <= 0.05);
    CHECK(hi - lo > 0.03);           // it does vary
    CHECK(max_step < 0.05 * 0.02);   // and smoothly (1 cm steps)
    TerrainSpec other = s;
    CHECK(roughness_at(other, 7.1, -3.3) == roughness_at(s, 7.1, -3.3));
    other.seed = 4;
    CHECK(roughness_at(other, 7.1, -3.3) != roughness_at(s, 7.1, -3.3));
}
