// Known-answer maps for the cell classes: flat, a box, a wall cell with a low mean but a
// high max, a face at the edge of what is known, one stray sample, a ditch, a drop in its
// rim's shadow, the top of a ditch's wall, a face within one cell, slopes below and above
// the limit, aged data.
#include <catch2/catch.hpp>

#include <cmath>

#include "ugv_test/terrain_grid_builder.hpp"
#include "ugv/traverse/cell_classifier.hpp"

using namespace ugv::traverse;
using namespace ugv::traverse::test;

namespace {

TraversabilityLayers classify(const TerrainGrid& g, const Odometer& odo = Odometer{},
                              const ClassifierConfig& config = ClassifierConfig{})
{
    CellClassifier c{config};
    TraversabilityLayers out;
    c.classify(g, odo, out);
    return out;
}

int count_class(const TraversabilityLayers& l, CellClass c)
{
    int n = 0;
    for (CellClass v : l.cell_class) n += v == c ? 1 : 0;
    return n;
}

std::size_t at(const TerrainGrid& g, double x, double y)
{
    const int i = static_cast<int>(std::floor((x - g.origin_x_m) / g.resolution_m));
    const int j = static_cast<int>(std::floor((y - g.origin_y_m) / g.resolution_m));
    return static_cast<std::size_t>(i) * g.ny + j;
}

constexpr double kGround = 1.5;  // not 0: nothing may assume the ground is at 0

}  // namespace

TEST_CASE("a flat map is all traversable at a low cost")
{
    TerrainGrid g = empty_grid();
    fill(g, [](double, double) { return kGround; });
    const TraversabilityLayers l = classify(g);
    CHECK(count_class(l, CellClass::traversable) == static_cast<int>(g.cells()));
    float worst = 0;
    for (float c : l.cost) worst = std::max(worst, c);
    CHECK(worst < 0.5f);
    CHECK(l.slope_deg[at(g, 10, 0)] < 3.0f);
}

TEST_CASE("unknown cells stay unknown and do not disturb their neighbours")
{
    TerrainGrid g = empty_grid(40, 40);
    fill(g, [](double, double) { return kGround; });
    const std::size_t hole = at(g, 3, 0);
    g.count[hole] = 0;
    g.mean_z_m[hole] = g.max_z_m[hole] = g.min_z_m[hole] = g.variance_z_m2[hole] = NAN;
    const TraversabilityLayers l = classify(g);
    CHECK(l.cell_class[hole] == CellClass::unknown);
    CHECK(std::isnan(l.cost[hole]));
    CHECK(count_class(l, CellClass::traversable) == static_cast<int>(g.cells()) - 1);
}

TEST_CASE("a box is an obstacle and the ground around it is not")
{
    TerrainGrid g = empty_grid();
    // 0.6 x 0.6 m, 0.5 m tall, 8 m ahead.
    auto box = [](double x, double y) { return x >= 8.0 && x < 8.6 && y >= -0.3 && y < 0.3; };
    fill(g, [&](double x, double y) { return kGround + (box(x, y) ? 0.5 : 0.0); });
    const TraversabilityLayers l = classify(g);
    CHECK(l.cell_class[at(g, 8.3, 0.1)] == CellClass::obstacle);
    CHECK(l.cell_class[at(g, 8.1, -0.2)] == CellClass::obstacle);
    CHECK(l.step_m[at(g, 8.3, 0.1)] > 0.45f);
    // Ground one cell away: not an obstacle, not a ditch.
    CHECK(l.cell_class[at(g, 7.7, 0.1)] == CellClass::traversable);
    CHECK(l.cell_class[at(g, 8.3, 0.5)] == CellClass::traversable);
    // The box's faces fall mid-cell: 4 x 4 cells hold some of it.
    CHECK(count_class(l, CellClass::obstacle) == 16);
    CHECK(count_class(l, CellClass::negative_obstacle) == 0);
}

TEST_CASE("a step radius of a whole number of cells covers them all at the map's float resolution")
{
    // The map message carries its resolution as a float: 0.2f is 0.2000000030 m, and 0.4 m
    // of it is 1.99999997 cells.
    TerrainGrid g = empty_grid(60, 60, static_cast<double>(0.2f));
    fill(g, [](double x, double) { return kGround - (x >= 8.0 ? 0.5 : 0.0); });
    const std::size_t two_cells_before = at(g, 7.7, 0.1);
    ClassifierConfig two;
    two.step_radius_m = 0.4;
    CHECK(classify(g, Odometer{}, two).step_m[two_cells_before] > 0.45f);
    ClassifierConfig one;
    one.step_radius_m = 0.3;
    CHECK(classify(g, Odometer{}, one).step_m[two_cells_before] < 0.1f);
}

TEST_CASE("a wall's cell with a low mean but a high, well supported max is an obstacle")
{
    TerrainGrid g = empty_grid(60, 60);
    fill(g, [](double, double) { return kGround; });
    // 20 samples: 17 on the ground in front of the face, 3 up the 2.5 m face.
    std::vector<double> z(17, kGround);
    for (double h : {1.0, 1.8, 2.5}) z.push_back(kGround + h);
    const std::size_t k = at(g, 5.1, 0.1);
    set_samples(g, static_cast<int>(k / g.ny), static_cast<int>(k % g.ny), z);
    REQUIRE(g.mean_z_m[k] - kGround < 0.3f);
    const TraversabilityLayers l = classify(g);
    CHECK(l.cell_class[k] == CellClass::obstacle);
    CHECK(l.span_m[k] > 2.4f);
}

TEST_CASE("a wall at range whose spread samples raise the means before it is still an obstacle")
{
    // The wall's face in one row of cells (cy 3.0), nothing seen behind it. At 14 m its samples
    // are spread (docs/terrain.md section 3.5): the ground cells before it hold shares of them
    // in their means (0.15 m up, above all their own samples: the published max is the mean),
    // never in their lowest samples (the ground's).
    TerrainGrid g = empty_grid(90, 60);
    fill(g, [](double, double) { return kGround; });
    auto cell = [&](int i, int j, int n, double mean, double sd, double max, double min) {
        const std::size_t k = static_cast<std::size_t>(i) * g.ny + j;
        g.count[k] = n;
        g.mean_z_m[k] = static_cast<float>(kGround + mean);
        g.variance_z_m2[k] = static_cast<float>(sd * sd);
        g.max_z_m[k] = static_cast<float>(kGround + max);
        g.min_z_m[k] = static_cast<float>(kGround + min);
    };
    std::vector<std::size_t> face;
    for (int i = 0; i < g.nx; ++i)
        for (int j = 0; j < g.ny; ++j) {
            const double x = cx(g, i), y = cy(g, j);
            if (y > 3.05) {
                cell(i, j, 0, NAN, NAN, NAN, NAN);
            } else if (x > 8 && x < 14 && y > 2.95) {
                cell(i, j, 16, 0.18, 0.105, 0.33, 0.17);
                face.push_back(static_cast<std::size_t>(i) * g.ny + j);
            } else if (x > 6 && x < 16 && y > 1.3) {
                cell(i, j, 17, 0.15, 0.11, 0.15, 0.0);
            }
        }
    const TraversabilityLayers l = classify(g);
    int obstacles = 0;
    for (std::size_t k : face) obstacles += l.cell_class[k] == CellClass::obstacle ? 1 : 0;
    CHECK(obstacles == static_cast<int>(face.size()));
    // The ground before it, its means raised, is not.
    CHECK(l.cell_class[at(g, 11.0, 2.5)] == CellClass::traversable);
    CHECK(l.cell_class[at(g, 11.0, 1.5)] == CellClass::traversable);
    CHECK(count_class(l, CellClass::obstacle) == static_cast<int>(face.size()));
    CHECK(l.ground_m[at(g, 11.0, 2.5)] < kGround + 0.05);
}

TEST_CASE("a face at the edge of what is known does not lift the ground behind it")
{
    // A wall 9 m ahead seen only up to 0.49 m, nothing known behind its face but one cell two
    // rows back holding a single sample of it (at 0.24 m). The face's cells, whose samples span
    // the face, are no ground level: fitted to them, the plane at the edge of what is known
    // tilted up to the wall and lifted the ground under that cell to its sample's height.
    TerrainGrid g = empty_grid(80, 60);
    fill(g, [](double, double) { return kGround; });
    std::vector<double> face;
    for (int s = 0; s < 24; ++s) face.push_back(kGround + 0.02 + 0.47 * s / 23.0);
    int face_row = -1;
    for (int i = 0; i < g.nx; ++i) {
        const double x = cx(g, i);
        if (x < 9.0) continue;
        if (face_row < 0) face_row = i;
        for (int j = 0; j < g.ny; ++j) {
            const std::size_t k = static_cast<std::size_t>(i) * g.ny + j;
            if (i == face_row) {
                set_samples(g, i, j, face);
            } else {
                g.count[k] = 0;
                g.mean_z_m[k] = g.variance_z_m2[k] = g.max_z_m[k] = g.min_z_m[k] = g.age_s[k] = NAN;
            }
        }
    }
    const int behind = face_row + 2, j = g.ny / 2;
    set_samples(g, behind, j, {kGround + 0.24});
    const std::size_t k = static_cast<std::size_t>(behind) * g.ny + j;
    const TraversabilityLayers l = classify(g);
    CHECK(l.cell_class[static_cast<std::size_t>(face_row) * g.ny + j] == CellClass::obstacle);
    CHECK(l.ground_m[k] < kGround + 0.03f);
    CHECK(l.cell_class[k] == CellClass::obstacle);
    // The ground before the face stays traversable.
    CHECK(l.cell_class[static_cast<std::size_t>(face_row - 2) * g.ny + j] == CellClass::traversable);
}

TEST_CASE("one stray sample does not make an obstacle")
{
    TerrainGrid g = empty_grid(60, 60);
    fill(g, [](double, double) { return kGround; });
    SECTION("in a well sampled cell")
    {
        std::vector<double> z(20, kGround);
        z.back() = kGround + 0.6;
        const std::size_t k = at(g, 5.1, 0.1);
        set_samples(g, static_cast<int>(k / g.ny), static_cast<int>(k % g.ny), z);
        const TraversabilityLayers l = classify(g);
        CHECK(l.cell_class[k] == CellClass::traversable);
        CHECK(count_class(l, CellClass::obstacle) == 0);
        CHECK(l.span_m[k] > 0.59f);  // the sample is still reported
    }
    SECTION("alone in its cell")
    {
        const std::size_t k = at(g, 5.1, 0.1);
        set_samples(g, static_cast<int>(k / g.ny), static_cast<int>(k % g.ny), {kGround + 0.6});
        const TraversabilityLayers l = classify(g);
        CHECK(l.cell_class[k] == CellClass::traversable);
        CHECK(count_class(l, CellClass::obstacle) == 0);
        CHECK(count_class(l, CellClass::negative_obstacle) == 0);
    }
    SECTION("two neighbouring cells of one sample each are an obstacle")
    {
        for (double y : {0.1, 0.3}) {
            const std::size_t k = at(g, 5.1, y);
            set_samples(g, static_cast<int>(k / g.ny), static_cast<int>(k % g.ny), {kGround + 0.6});
        }
        const TraversabilityLayers l = classify(g);
        CHECK(l.cell_class[at(g, 5.1, 0.1)] == CellClass::obstacle);
        CHECK(l.cell_class[at(g, 5.1, 0.3)] == CellClass::obstacle);
    }
}

TEST_CASE("a ditch is a negative obstacle")
{
    TerrainGrid g = empty_grid();
    // 1 m wide, 0.4 m deep, across the path 10 m ahead (its edges fall mid-cell: the cells
    // from 9.9 to 10.1 and 10.9 to 11.1 hold both levels).
    fill(g, [](double x, double) { return kGround - (x >= 10.0 && x < 11.0 ? 0.4 : 0.0); });
    const TraversabilityLayers l = classify(g);
    CHECK(l.cell_class[at(g, 10.1, 0.1)] == CellClass::negative_obstacle);
    CHECK(l.cell_class[at(g, 10.9, -2.1)] == CellClass::negative_obstacle);
    CHECK(l.drop_m[at(g, 10.1, 0.1)] > 0.35f);
    // The rims stay traversable; nothing is a positive obstacle.
    CHECK(l.cell_class[at(g, 9.7, 0.1)] == CellClass::traversable);
    CHECK(l.cell_class[at(g, 11.3, 0.1)] == CellClass::traversable);
    CHECK(count_class(l, CellClass::obstacle) == 0);
}

TEST_CASE("the cell that holds the top of a ditch's wall is a negative obstacle")
{
    // A ditch 0.3 m deep, its floor from x = 10.1 to 11.1 (cell boundaries); its far wall, at
    // x = 11.1, faces the laser. The cells before it hold the floor; the cell from 11.1 to
    // 11.3 holds the ground and the wall's top 0.13 m (the laser saw no lower): a face up
    // from the floor, with the floor's drop beside it. The truth counts the wall's columns.
    TerrainGrid g = empty_grid();
    fill(g, [](double x, double) { return kGround - (x >= 10.1 && x < 11.1 ? 0.3 : 0.0); });
    const std::size_t wall = at(g, 11.2, 0.1), beyond = at(g, 11.4, 0.1);
    SECTION("the wall's cell, with samples down the wall")
    {
        set_samples(g, static_cast<int>(wall / g.ny), static_cast<int>(wall % g.ny),
                    {kGround, kGround, kGround - 0.01, kGround - 0.05, kGround - 0.1, kGround - 0.13, kGround - 0.13});
        const TraversabilityLayers l = classify(g);
        CHECK(l.cell_class[at(g, 10.5, 0.1)] == CellClass::negative_obstacle);
        CHECK(l.cell_class[wall] == CellClass::negative_obstacle);
        // Not the ground behind it, and nothing is a positive obstacle.
        CHECK(l.cell_class[beyond] == CellClass::traversable);
        CHECK(count_class(l, CellClass::obstacle) == 0);
    }
    SECTION("a cell of ground beside the floor, its samples all level, stays traversable")
    {
        const TraversabilityLayers l = classify(g);
        CHECK(l.cell_class[wall] == CellClass::traversable);
        CHECK(l.cell_class[beyond] == CellClass::traversable);
    }
}

TEST_CASE("a drop whose face lies in its rim's shadow makes the rim a negative obstacle")
{
    // A wide ditch from x = 6.1 on (a cell boundary); the laser, looking over the rim, never
    // sees its near wall: the rows of cells from 6.1 to 6.1 + shadow_m are unknown. The floor
    // is wider than the ground radius, so it is its own local ground, and no step window
    // spans the gap.
    auto shadowed = [](double depth_m, double shadow_m = 0.2) {
        TerrainGrid g = empty_grid(80, 80);
        fill(g, [=](double x, double) { return kGround - (x >= 6.1 ? depth_m : 0.0); });
        for (int i = 0; i < g.nx; ++i)
            for (int j = 0; j < g.ny; ++j)
                if (cx(g, i) > 6.1 && cx(g, i) < 6.1 + shadow_m) {
                    const std::size_t k = static_cast<std::size_t>(i) * g.ny + j;
                    g.count[k] = 0;
                    g.mean_z_m[k] = g.max_z_m[k] = g.min_z_m[k] = g.variance_z_m2[k] = NAN;
                }
        return g;
    };
    SECTION("0.3 m deep: the rim is the top of a drop")
    {
        const TerrainGrid g = shadowed(0.3);
        const TraversabilityLayers l = classify(g);
        CHECK(l.cell_class[at(g, 6.0, 0.1)] == CellClass::negative_obstacle);
        CHECK(l.cell_class[at(g, 6.0, -3.1)] == CellClass::negative_obstacle);
        CHECK(l.drop_m[at(g, 6.0, 0.1)] > 0.27f);
        CHECK(l.cell_class[at(g, 6.2, 0.1)] == CellClass::unknown);
        // The ground before the rim and the floor beyond the gap are not.
        CHECK(l.cell_class[at(g, 5.6, 0.1)] == CellClass::traversable);
        CHECK(l.cell_class[at(g, 6.6, 0.1)] == CellClass::traversable);
        CHECK(count_class(l, CellClass::obstacle) == 0);
    }
    SECTION("a shadow of 3 cells: across it within shadow_radius_m (0.6 m), not within 0.5 m")
    {
        // 0.3 m over the 0.6 m between the centres: steeper than 25 degrees.
        const TerrainGrid g = shadowed(0.3, 0.4);
        const TraversabilityLayers l = classify(g);
        CHECK(l.cell_class[at(g, 6.0, 0.1)] == CellClass::negative_obstacle);
        CHECK(l.cell_class[at(g, 6.4, 0.1)] == CellClass::unknown);
        ClassifierConfig nearer;
        nearer.shadow_radius_m = 0.5;
        CHECK(classify(g, Odometer{}, nearer).cell_class[at(g, 6.0, 0.1)] == CellClass::traversable);
    }
    SECTION("0.25 m across a shadow of 3 cells: gentler than max_slope_deg, no drop")
    {
        const TerrainGrid g = shadowed(0.25, 0.4);
        CHECK(classify(g).cell_class[at(g, 6.0, 0.1)] == CellClass::traversable);
    }
    SECTION("0.15 m deep: less than max_drop, no drop")
    {
        const TerrainGrid g = shadowed(0.15);
        const TraversabilityLayers l = classify(g);
        CHECK(l.cell_class[at(g, 6.0, 0.1)] == CellClass::traversable);
        CHECK(count_class(l, CellClass::negative_obstacle) == 0);
    }
}

TEST_CASE("a vertical face is an obstacle where the local ground does not show it")
{
    // A 5 degree ramp 3 m wide, rising 0.35 m over 4 m along the path: its sides are
    // vertical faces as tall as the ramp. Where a side stands 0.25 m or more, its cells are
    // obstacles; where it is under 0.2 m, traversable; the ramp's top surface is too.
    TerrainGrid g = empty_grid(80, 80);
    auto ramp = [](double x, double y) { return x >= 8.0 && x < 12.0 && y >= -1.5 && y < 1.5 ? 0.35 * (x - 8.0) / 4.0 : 0.0; };
    fill(g, [&](double x, double y) { return kGround + ramp(x, y); });
    const TraversabilityLayers l = classify(g);
    for (double x : {11.1, 11.5})
        for (double y : {1.4, -1.4}) CHECK(l.cell_class[at(g, x, y)] == CellClass::obstacle);
    for (double y : {1.3, 0.1, -1.3}) CHECK(l.cell_class[at(g, 9.1, y)] == CellClass::traversable);
    for (double x : {9.5, 10.5, 11.1}) CHECK(l.cell_class[at(g, x, 0.1)] == CellClass::traversable);
    CHECK(l.cell_class[at(g, 11.1, 1.7)] == CellClass::traversable);  // the ground beside the face
    // The rule's second half: a step between extremes alone, the means level (the spread of
    // passes seen with different pose errors), is not a face.
    TerrainGrid spread = empty_grid(40, 40);
    fill(spread, [](double, double) { return kGround; });
    const std::size_t k = at(spread, 4.1, 0.1);
    set_samples(spread, static_cast<int>(k / spread.ny), static_cast<int>(k % spread.ny),
                {kGround - 0.06, kGround - 0.03, kGround, kGround, kGround + 0.03, kGround + 0.06, kGround + 0.1,
                 kGround + 0.12, kGround + 0.14, kGround + 0.16, kGround - 0.02, kGround - 0.04});
    const std::size_t low = k + 1;
    set_samples(spread, static_cast<int>(low / spread.ny), static_cast<int>(low % spread.ny),
                {kGround - 0.08, kGround - 0.06, kGround - 0.02, kGround, kGround + 0.02, kGround + 0.05});
    const TraversabilityLayers s = classify(spread);
    REQUIRE(s.step_m[k] >= 0.2f);
    CHECK(s.cell_class[k] == CellClass::traversable);
}

TEST_CASE("a face within one cell is an obstacle when the cell's mean leaves the ground")
{
    // Neither extreme stands max_step (max_drop) from the ground, but they stand max_step
    // apart (the cell holds a wall's edge, seen down to 0.19 m below the rim or up to 0.19 m
    // above the foot) and the mean has moved with them. The cell going up also meets the
    // vertical-face rule (its own bottom lies in its step window); the one going down only
    // this rule.
    TerrainGrid g = empty_grid(40, 40);
    fill(g, [](double, double) { return kGround; });
    const std::size_t down = at(g, 4.1, 0.1), up = at(g, 4.1, -2.1);
    auto put = [&](std::size_t k, double sign) {
        std::vector<double> z;
        for (double d : {0.02, 0.01, -0.05, -0.1, -0.15, -0.18, -0.19, -0.19}) z.push_back(kGround + sign * d);
        set_samples(g, static_cast<int>(k / g.ny), static_cast<int>(k % g.ny), z);
    };
    put(down, 1.0);
    put(up, -1.0);
    const TraversabilityLayers l = classify(g);
    CHECK(l.cell_class[down] == CellClass::negative_obstacle);
    CHECK(l.cell_class[up] == CellClass::obstacle);
    CHECK(count_class(l, CellClass::obstacle) == 1);
    CHECK(count_class(l, CellClass::negative_obstacle) == 1);
    // 0.18 m apart: no face.
    for (std::size_t k : {down, up}) {
        const int i = static_cast<int>(k / g.ny), j = static_cast<int>(k % g.ny);
        const double s = k == down ? 1.0 : -1.0;
        set_samples(g, i, j, {kGround + s * 0.01, kGround + s * 0.01, kGround - s * 0.1, kGround - s * 0.17, kGround - s * 0.17});
    }
    const TraversabilityLayers flat = classify(g);
    CHECK(flat.cell_class[down] == CellClass::traversable);
    CHECK(flat.cell_class[up] == CellClass::traversable);
}

TEST_CASE("a slope below the limit is traversable, one above it is not")
{
    TerrainGrid g = empty_grid(80, 80);
    SECTION("15 degrees")
    {
        const double t = std::tan(15.0 * M_PI / 180.0);
        fill(g, [&](double x, double) { return kGround + x * t; });
        const TraversabilityLayers l = classify(g);
        CHECK(count_class(l, CellClass::traversable) == static_cast<int>(g.cells()));
        CHECK(l.slope_deg[at(g, 6, 0)] > 13.0f);
        CHECK(l.slope_deg[at(g, 6, 0)] < 17.0f);
        CHECK(l.cost[at(g, 6, 0)] > 0.4f);  // it costs
    }
    SECTION("35 degrees")
    {
        const double t = std::tan(35.0 * M_PI / 180.0);
        fill(g, [&](double x, double y) { return kGround + (x > 5 ? (x - 5) * t : 0.0) + 0 * y; });
        const TraversabilityLayers l = classify(g);
        CHECK(l.cell_class[at(g, 8.1, 0.1)] == CellClass::obstacle);
        CHECK(l.cell_class[at(g, 3.1, 0.1)] == CellClass::traversable);
    }
    SECTION("20 degrees across the path")
    {
        const double t = std::tan(20.0 * M_PI / 180.0);
        fill(g, [&](double, double y) { return kGround + y * t; });
        const TraversabilityLayers l = classify(g);
        CHECK(count_class(l, CellClass::traversable) == static_cast<int>(g.cells()));
        CHECK(l.slope_deg[at(g, 6, 0)] > 18.0f);
    }
}

TEST_CASE("aged data decays to unknown, by time and by distance driven")
{
    TerrainGrid g = empty_grid(40, 40);
    fill(g, [](double, double) { return kGround; });
    const std::size_t old = at(g, 3, 0), half = at(g, 4, 0), fresh = at(g, 5, 0);
    g.age_s[old] = 61;   // beyond max_age_s
    g.age_s[half] = 30;  // half of it
    g.age_s[fresh] = 0;
    SECTION("standing still: by age")
    {
        const TraversabilityLayers l = classify(g);
        CHECK(l.cell_class[old] == CellClass::unknown);
        CHECK(l.certainty[old] == 0.0f);
        CHECK(l.cell_class[half] == CellClass::traversable);
        CHECK(std::abs(l.certainty[half] - 0.5f) < 1e-3f);
        CHECK(l.certainty[fresh] == 1.0f);
    }
    SECTION("driving: by distance")
    {
        Odometer odo;
        // 2 m/s for 30 s: the cell aged 30 s was seen 60 m of driving ago.
        for (int t = 0; t <= 30; ++t) odo.add(1'000'000 + t * 1'000'000LL, Eigen::Vector3d(2.0 * t, 0, kGround));
        const TraversabilityLayers l = classify(g, odo);
        CHECK(l.cell_class[half] == CellClass::unknown);
        CHECK(l.certainty[half] == 0.0f);
        // Aged 0.1 s (the builder's default): 0.2 m driven of 40.
        CHECK(l.certainty[at(g, 6, 0)] > 0.99f);
    }
}

TEST_CASE("bad classifier settings are refused")
{
    ClassifierConfig c;
    c.max_step_m = 0;
    CHECK_THROWS(CellClassifier{c});
    c = ClassifierConfig{};
    c.max_slope_deg = 90;
    CHECK_THROWS(CellClassifier{c});
    c = ClassifierConfig{};
    c.max_age_s = NAN;
    CHECK_THROWS(CellClassifier{c});
    c = ClassifierConfig{};
    c.face_mean_step_m = -0.1;
    CHECK_THROWS(CellClassifier{c});
}

TEST_CASE("the separable slope equals the plain plane fit")
{
    TerrainGrid g = empty_grid(60, 70);
    // Smooth hills up to about 20 degrees, no steps, some cells unknown.
    fill(g, [](double x, double y) { return kGround + 0.4 * std::sin(0.5 * x) * std::cos(0.4 * y) + 0.1 * x; });
    for (std::size_t k = 0; k < g.cells(); k += 7) {
        g.count[k] = 0;
        g.mean_z_m[k] = g.max_z_m[k] = g.min_z_m[k] = g.variance_z_m2[k] = NAN;
    }
    const TraversabilityLayers l = classify(g);
    REQUIRE(count_class(l, CellClass::obstacle) == 0);
    std::vector<uint8_t> counted(g.cells());
    for (std::size_t k = 0; k < g.cells(); ++k) counted[k] = g.count[k] > 0 ? 1 : 0;
    const int h = 2;  // slope_radius_m 0.5 at 0.2 m
    int compared = 0;
    for (int i = 0; i < g.nx; ++i)
        for (int j = 0; j < g.ny; ++j) {
            const std::size_t k = static_cast<std::size_t>(i) * g.ny + j;
            if (!counted[k]) continue;
            const double ref = slope_reference_deg(g, counted, i, j, h);
            INFO("cell " << i << ", " << j);
            REQUIRE(std::isnan(ref) == std::isnan(l.slope_deg[k]));
            if (std::isnan(ref)) continue;
            CHECK(std::abs(ref - l.slope_deg[k]) < 0.05);
            ++compared;
        }
    CHECK(compared > 3000);
}

TEST_CASE("a cell holding only its neighbours' spread shares was not seen")
{
    TerrainGrid g = empty_grid(40, 40);
    fill(g, [](double, double) { return kGround; });
    // Inside a ditch the laser never saw: the terrain map shows the rim's spread shares
    // (max = min = mean, several counted).
    const std::size_t k = at(g, 3.1, 0.1);
    g.count[k] = 9;
    g.mean_z_m[k] = g.max_z_m[k] = g.min_z_m[k] = static_cast<float>(kGround - 0.02);
    g.variance_z_m2[k] = 0.0004f;
    const TraversabilityLayers l = classify(g);
    CHECK(l.cell_class[k] == CellClass::unknown);
    CHECK(std::isnan(l.cost[k]));
}
