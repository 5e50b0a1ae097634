#include <catch2/catch.hpp>

#include "ugv/terrain/spread.hpp"

using namespace ugv::terrain;

TEST_CASE("a footprint inside one cell stays in that cell")
{
    const AxisFootprint f = axis_footprint(5.5f, 0.25f, 10);
    REQUIRE(f.count == 1);
    CHECK(f.first == 5);
    CHECK(f.fraction[0] == Approx(1.0f));
    CHECK(f.centre[0] == Approx(0.0f).margin(1e-6));
}

TEST_CASE("a footprint is shared by area")
{
    // [4.0, 6.0] over cells 4 and 5... centre 5.0, half-width 1.0 -> cells 4 and 5, half each.
    AxisFootprint f = axis_footprint(5.0f, 1.0f, 10);
    REQUIRE(f.count == 2);
    CHECK(f.first == 4);
    CHECK(f.fraction[0] == Approx(0.5f));
    CHECK(f.fraction[1] == Approx(0.5f));
    // [4.75, 6.25]: cell 4 gets 0.25/1.5, cell 5 1/1.5, cell 6 0.25/1.5.
    f = axis_footprint(5.5f, 0.75f, 10);
    REQUIRE(f.count == 3);
    CHECK(f.first == 4);
    CHECK(f.fraction[0] == Approx(1.0f / 6.0f));
    CHECK(f.fraction[1] == Approx(4.0f / 6.0f));
    CHECK(f.fraction[2] == Approx(1.0f / 6.0f));
    CHECK(f.centre[0] == Approx(0.375f));   // overlap [4.75, 5) centre 4.875 from 4.5
    CHECK(f.centre[2] == Approx(-0.375f));
}

TEST_CASE("at the map edge the inside share is renormalised; outside is empty")
{
    const AxisFootprint f = axis_footprint(0.5f, 1.5f, 10);  // [-1, 2] -> [0, 2]
    REQUIRE(f.count == 2);
    CHECK(f.first == 0);
    CHECK(f.fraction[0] + f.fraction[1] == Approx(1.0f));
    CHECK(axis_footprint(-3.0f, 1.0f, 10).count == 0);
    CHECK(axis_footprint(12.5f, 1.0f, 10).count == 0);
}

TEST_CASE("the half-width is capped at kMaxSpreadCells")
{
    const AxisFootprint f = axis_footprint(50.5f, 100.0f, 100);
    CHECK(f.count == 2 * kMaxSpreadCells + 1);
    float total = 0.0f;
    for (int k = 0; k < f.count; ++k) total += f.fraction[k];
    CHECK(total == Approx(1.0f));
}
