#include <catch2/catch.hpp>

#include <cmath>

#include "ugv/terrain/egocentric_grid.hpp"

using namespace ugv::terrain;

namespace {

// Fuses one unit-weight sample at local (x, y) with height z.
void put(EgocentricGrid& g, float x, float y, double z)
{
    float xr = 0, yr = 0;
    const int cell = g.locate(x, y, xr, yr);
    REQUIRE(cell >= 0);
    g.fuse(cell, xr, yr, z, 1.0f);
}

double mean_z(const CellSums& c)
{
    return cell_statistics(c, StatisticsKind::variance_weighted).mean_z_m;
}

}  // namespace

TEST_CASE("eq. 5-7: local position to cell, centred in Y, nothing wrapped in")
{
    EgocentricGrid g(150, 150, 0.2);
    float xr = 0, yr = 0;
    // x = 1.05 m -> row 5 (centre 1.1), y = 0.05 m -> column 75 (centre 0.1): offsets -0.05, -0.05.
    const int cell = g.locate(1.05f, 0.05f, xr, yr);
    CHECK(cell == 5 * 150 + 75);
    CHECK(xr == Approx(-0.05f));
    CHECK(yr == Approx(-0.05f));
    CHECK(g.locate(-0.01f, 0.0f, xr, yr) == -1);  // behind the reference point
    CHECK(g.locate(30.0f, 0.0f, xr, yr) == -1);   // beyond X_max: not wrapped onto row 0
    CHECK(g.locate(1.0f, 15.0f, xr, yr) == -1);
    CHECK(g.locate(1.0f, -15.01f, xr, yr) == -1);
    CHECK(g.locate(1.0f, -14.99f, xr, yr) == 5 * 150 + 0);
}

TEST_CASE("wrap_forward clears the rows left behind and re-indexes the rest (eq. 6, 8)")
{
    EgocentricGrid g(10, 4, 1.0);
    for (int i = 0; i < 10; ++i) put(g, static_cast<float>(i) + 0.5f, 0.5f, i);
    g.wrap_forward(3);
    CHECK(g.wrap_index() == 3);
    // Unwrapped row 0 is the old row 3 ... row 6 is the old row 9; rows 7-9 are cleared.
    for (int i = 0; i < 7; ++i) CHECK(mean_z(g.at(i, 2)) == Approx(i + 3));
    for (int i = 7; i < 10; ++i) CHECK(g.at(i, 2).empty());
    // A new point at the far end lands in the recycled physical row.
    put(g, 9.5f, 0.5f, 42.0);
    CHECK(mean_z(g.at(9, 2)) == 42.0);
    CHECK(g.physical(9, 2) == ((9 + 3) % 10) * 4 + 2);
    g.wrap_backward(2);
    CHECK(g.wrap_index() == 1);
    CHECK(g.at(0, 2).empty());
    CHECK(g.at(1, 2).empty());
    CHECK(mean_z(g.at(2, 2)) == Approx(3.0));
}

TEST_CASE("transform by 90 deg moves a cell's content to where the world point now is")
{
    EgocentricGrid g(50, 50, 0.2);  // x 0..10, y -5..5
    put(g, 4.1f, 2.1f, 1.0);
    const int dropped = g.transform(M_PI / 2, 0.0, 0.0);
    CHECK(dropped == 0);
    // The frame turned left by 90 deg: a point at (4.1, 2.1) is now at (2.1, -4.1).
    float xr = 0, yr = 0;
    const int cell = g.locate(2.1f, -4.1f, xr, yr);
    REQUIRE(cell >= 0);
    CHECK(g.count(cell) == 1);
    CHECK(mean_z(g.at(cell)) == 1.0);
    float x_re = 0, y_re = 0;
    mean_offset(g.at(cell), x_re, y_re);
    CHECK(x_re == Approx(0.0f).margin(1e-5));
    CHECK(y_re == Approx(0.0f).margin(1e-5));
}

TEST_CASE("the remainders of eq. 15-16 cancel quantisation over many small rotations")
{
    EgocentricGrid g(100, 100, 0.2);  // x 0..20, y -10..10
    put(g, 12.3f, 0.1f, 7.0);
    // 18 rotations of 5 deg: without remainders each would snap to a cell centre and the
    // error would grow by up to half a cell per step.
    for (int k = 0; k < 18; ++k) g.transform(5.0 * M_PI / 180.0, 0.0, 0.0);
    // (12.3, 0.1) turned by -90 deg about the origin: (0.1, -12.3).
    float xr = 0, yr = 0;
    const int cell = g.locate(0.1f, -12.3f, xr, yr);
    CHECK(cell == -1);  // y = -12.3 is outside +/-10: dropped, as the grid says
    EgocentricGrid h(100, 100, 0.2);
    put(h, 8.3f, 0.1f, 7.0);
    for (int k = 0; k < 18; ++k) h.transform(5.0 * M_PI / 180.0, 0.0, 0.0);
    const int c2 = h.locate(0.1f, -8.3f, xr, yr);
    REQUIRE(c2 >= 0);
    REQUIRE(h.count(c2) == 1);
    float x_re = 0, y_re = 0;
    mean_offset(h.at(c2), x_re, y_re);
    // The sample's position is kept to within float rounding, not half a cell.
    CHECK(h.centre_x_m(0) + x_re == Approx(0.1f).margin(1e-3));
    CHECK(h.centre_y_m(8) + y_re == Approx(-8.3f).margin(1e-3));
    CHECK(c2 == h.physical(0, 8));
}

TEST_CASE("a pure shift by whole columns keeps the remainders")
{
    EgocentricGrid g(10, 10, 1.0);  // y -5..5
    put(g, 3.25f, 1.75f, 2.0);
    g.transform(0.0, 0.0, 1.0);  // the frame moves 1 m to the left: the point is at y = 0.75
    float xr = 0, yr = 0;
    const int cell = g.locate(3.25f, 0.75f, xr, yr);
    REQUIRE(g.count(cell) == 1);
    float x_re = 0, y_re = 0;
    mean_offset(g.at(cell), x_re, y_re);
    CHECK(x_re == Approx(-0.25f));
    CHECK(y_re == Approx(0.25f));
}
