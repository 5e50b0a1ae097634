// One update: malformed maps counted and dropped, counters, determinism.
#include <catch2/catch.hpp>

#include <cmath>

#include "ugv_test/terrain_grid_builder.hpp"
#include "ugv/traverse/traversability.hpp"

using namespace ugv::traverse;
using namespace ugv::traverse::test;

namespace {

TerrainGrid box_world()
{
    TerrainGrid g = empty_grid();
    fill(g, [](double x, double y) { return 1.5 + (x >= 8.0 && x < 9.0 && std::abs(y) < 0.5 ? 0.5 : 0.0); });
    return g;
}

}  // namespace

TEST_CASE("malformed maps are counted and dropped, and change nothing")
{
    Traversability t{TraverseConfig{}};
    TerrainGrid good = box_world();
    REQUIRE(t.update(good));
    const auto before = t.result().layers.cell_class;
    const uint64_t obstacles = t.counters().obstacle_cells;
    REQUIRE(obstacles > 0);

    auto bad = [&](auto&& spoil, const char* why) {
        TerrainGrid g = box_world();
        g.utime_us = good.utime_us + 1'000'000;
        spoil(g);
        INFO(why);
        CHECK_FALSE(t.update(g));
        CHECK_FALSE(t.why().empty());
    };
    bad([](TerrainGrid& g) { g.mean_z_m.pop_back(); }, "short layer");
    bad([](TerrainGrid& g) { g.resolution_m = NAN; }, "NaN resolution");
    bad([](TerrainGrid& g) { g.nx = -3; }, "negative size");
    bad([](TerrainGrid& g) { g.mean_z_m[100] = INFINITY; }, "infinite mean in a known cell");
    bad([](TerrainGrid& g) { g.max_z_m[100] = NAN; }, "NaN max in a known cell");
    bad([](TerrainGrid& g) { g.max_z_m[100] = g.min_z_m[100] - 1; }, "max below min");
    bad([](TerrainGrid& g) { g.count[7] = -1; }, "negative count");
    bad([](TerrainGrid& g) { g.position_m.x() = NAN; }, "NaN position");
    CHECK(t.counters().maps_malformed == 8);
    CHECK(t.counters().maps_in == 9);
    CHECK(t.result().layers.cell_class == before);
    CHECK(t.counters().obstacle_cells == obstacles);

    // The same map again is a repeat; a good later one goes through.
    CHECK_FALSE(t.update(good));
    CHECK(t.counters().maps_duplicate == 1);
    good.utime_us += 500'000;
    CHECK(t.update(good));
}

TEST_CASE("counters say what the last map holds")
{
    Traversability t{TraverseConfig{}};
    TerrainGrid g = box_world();
    g.age_s[0] = 100;  // decayed
    REQUIRE(t.update(g));
    const TraverseCounters& c = t.counters();
    CHECK(c.obstacle_cells > 0);
    CHECK(c.negative_obstacle_cells == 0);
    CHECK(c.decayed_cells == 1);
    CHECK(c.unknown_cells == 1);
    CHECK(c.arcs_blocked >= 1);
    CHECK(c.arcs_blocked < 25);
    int visited = 0;
    c.visit([&](const char*, uint64_t) { ++visited; });
    CHECK(visited == 9);
}

TEST_CASE("the same map gives the same result, and a restarted log is taken")
{
    Traversability a{TraverseConfig{}}, b{TraverseConfig{}};
    TerrainGrid g = box_world();
    REQUIRE(a.update(g));
    REQUIRE(b.update(g));
    CHECK(a.result().layers.cell_class == b.result().layers.cell_class);
    CHECK(a.result().layers.cost == b.result().layers.cost);
    REQUIRE(a.result().arcs.size() == b.result().arcs.size());
    for (std::size_t k = 0; k < a.result().arcs.size(); ++k)
        CHECK(a.result().arcs[k].clear_distance_m == b.result().arcs[k].clear_distance_m);
    g.utime_us -= 100'000;  // the log played again from its start
    CHECK(a.update(g));
    CHECK(a.counters().time_restarts == 1);
}

TEST_CASE("a bad configuration is refused at construction")
{
    TraverseConfig c;
    c.arcs.count = 0;
    CHECK_THROWS(Traversability{c});
    c = TraverseConfig{};
    c.classifier.max_drop_m = -1;
    CHECK_THROWS(Traversability{c});
}
