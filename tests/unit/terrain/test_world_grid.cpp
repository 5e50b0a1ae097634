#include <catch2/catch.hpp>

#include "ugv/terrain/world_grid.hpp"

using namespace ugv::terrain;

TEST_CASE("the world ring follows the vehicle by whole cells and clears what leaves")
{
    WorldGrid g(10, 1.0);
    CHECK(g.follow({0.5, 0.5}) == 0);
    CHECK(g.corner_m().x() == -5.0);
    CHECK(g.corner_m().y() == -5.0);
    // A sample at ENU (-4.5, 0.5): window-local (0.5, 5.5).
    float xr = 0, yr = 0;
    int cell = g.locate(0.5f, 5.5f, xr, yr);
    REQUIRE(cell >= 0);
    g.fuse(cell, xr, yr, 3.0, 1.0f, 0);
    REQUIRE(g.cell_at({-4.5, 0.5}) == cell);
    CHECK(g.count(cell) == 1);
    // Two cells east: the western column (ENU x -5..-3) leaves and is cleared.
    CHECK(g.follow({2.5, 0.5}) == 2);
    CHECK(g.corner_m().x() == -3.0);
    CHECK(g.cell_at({-4.5, 0.5}) == -1);
    // The same physical row now holds ENU x 5..6: empty.
    REQUIRE(g.cell_at({5.5, 0.5}) >= 0);
    CHECK(g.count(g.cell_at({5.5, 0.5})) == 0);
    CHECK(g.at(g.cell_at({5.5, 0.5})).empty());
    // Back west: the sample was cleared, it does not come back.
    g.follow({0.5, 0.5});
    CHECK(g.count(g.cell_at({-4.5, 0.5})) == 0);
}

TEST_CASE("a jump larger than the window clears it all")
{
    WorldGrid g(10, 1.0);
    g.follow({0.0, 0.0});
    float xr = 0, yr = 0;
    g.fuse(g.locate(5.5f, 5.5f, xr, yr), xr, yr, 1.0, 1.0f, 0);
    g.follow({100.0, 0.0});
    g.follow({0.0, 0.0});
    for (int k = 0; k < 100; ++k) CHECK((g.count(k) == 0 && g.at(k).empty()));
}
