#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>
#include <vector>

#include "ugv/terrain/egocentric_grid.hpp"
#include "ugv/terrain/simd.hpp"

using namespace ugv::terrain;

namespace {

// Fuses one unit-weight sample at local (x, y) with height z.
void put(EgocentricGrid& g, float x, float y, double z)
{
    float xr = 0, yr = 0;
    const int cell = g.locate(x, y, xr, yr);
    REQUIRE(cell >= 0);
    g.fuse(cell, xr, yr, z, 1.0f, 0);
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

// The known cells' sums live in a pool (egocentric_grid.hpp): slots freed by wraps are
// reused, and once a quarter of them are free the pool is compacted. Whatever the slots
// do, each cell must read back exactly what was fused into it, as a plain array of sums
// fused the same way gives.
TEST_CASE("the pool of known cells gives each cell its own sums through fusion, wraps, compaction and clear")
{
    EgocentricGrid g(30, 20, 0.5);
    std::vector<CellSums> plain(600);
    std::vector<uint32_t> plain_n(600, 0);
    std::vector<CellExtremes> plain_e(600);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    const auto fuse_some = [&](int samples) {
        for (int k = 0; k < samples; ++k) {
            const float x = 15.0f * unit(rng), y = -5.0f + 10.0f * unit(rng);
            float xr = 0, yr = 0;
            const int cell = g.locate(x, y, xr, yr);
            if (cell < 0) continue;
            const double z = 100.0 + unit(rng);
            const float w = 1.0f + 9.0f * unit(rng);
            g.fuse(cell, xr, yr, z, w, 0);
            fuse_sample(plain[static_cast<std::size_t>(cell)], xr, yr, z, w);
            ++plain_n[static_cast<std::size_t>(cell)];
            plain_e[static_cast<std::size_t>(cell)].add(static_cast<float>(z));
        }
    };
    // Rows (unwrapped) first .. first + rows - 1 of the plain array made empty, as a wrap does.
    const auto clear_plain = [&](int first, int rows) {
        for (int i = first; i < first + rows; ++i)
            for (int j = 0; j < 20; ++j) {
                plain[static_cast<std::size_t>(g.physical(i, j))] = CellSums{};
                plain_n[static_cast<std::size_t>(g.physical(i, j))] = 0;
                plain_e[static_cast<std::size_t>(g.physical(i, j))] = CellExtremes{};
            }
    };
    const auto check_all = [&]() {
        int known = 0;
        for (int cell = 0; cell < 600; ++cell) {
            const CellSums& a = g.at(cell);
            const CellSums& b = plain[static_cast<std::size_t>(cell)];
            INFO("cell " << cell);
            REQUIRE(a.empty() == b.empty());
            CHECK(g.count(cell) == plain_n[static_cast<std::size_t>(cell)]);
            const CellExtremes& e = plain_e[static_cast<std::size_t>(cell)];
            if (b.empty()) {
                CHECK(std::isnan(g.extremes(cell).z_max_m));
                CHECK(std::isnan(g.extremes(cell).z_min_m));
                continue;
            }
            CHECK(g.extremes(cell).z_max_m == e.z_max_m);
            CHECK(g.extremes(cell).z_min_m == e.z_min_m);
            ++known;
            CHECK(a.w == b.w);
            CHECK(a.x_wx == b.x_wx);
            CHECK(a.y_wy2 == b.y_wy2);
            CHECK(a.z_ref_m == b.z_ref_m);
            CHECK(a.z_wz2 == b.z_wz2);
        }
        CHECK(g.known_cells() == known);
    };
    fuse_some(1500);
    check_all();
    clear_plain(0, 4);
    g.wrap_forward(4);  // 80 slots freed: fewer than a quarter, so they stay free in place
    check_all();
    fuse_some(300);  // new cells take the freed slots
    check_all();
    g.wrap_backward(3);  // the far rows cleared
    clear_plain(0, 3);
    check_all();
    clear_plain(0, 12);
    g.wrap_forward(12);  // over a quarter free: the pool is compacted
    check_all();
    fuse_some(800);
    check_all();
    g.clear();
    for (auto& c : plain) c = CellSums{};
    std::fill(plain_n.begin(), plain_n.end(), 0u);
    std::fill(plain_e.begin(), plain_e.end(), CellExtremes{});
    check_all();
    fuse_some(200);
    check_all();
}

TEST_CASE("a grid too large for the rotation's index arithmetic is refused")
{
    CHECK_THROWS_WITH(EgocentricGrid(4096, 2048, 0.2), Catch::Contains("4096 x 2048 cells"));
    CHECK_THROWS_AS(EgocentricGrid(0, 10, 0.2), std::invalid_argument);
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

namespace {

// False, with a warning, where the CPU cannot run the level's code.
bool cpu_runs(SimdLevel level)
{
    if (static_cast<int>(level) <= static_cast<int>(best_simd_level())) return true;
    WARN("skipped: this CPU cannot run the " << to_string(level) << " code");
    return false;
}

// One to three samples at random places and heights into each cell, but for a share
// skip_share of the cells, chosen at random.
void fuse_random(EgocentricGrid& g, std::mt19937& rng, float skip_share)
{
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    for (int i = 0; i < g.nx(); ++i) {
        for (int j = 0; j < g.ny(); ++j) {
            if (unit(rng) < skip_share) continue;
            for (int k = 1 + static_cast<int>(unit(rng) * 3); k > 0; --k) {
                float xr = 0, yr = 0;
                const float x = (static_cast<float>(i) + 0.05f + 0.9f * unit(rng)) * 0.25f;
                const float y = static_cast<float>(g.y_min_m()) + (static_cast<float>(j) + 0.05f + 0.9f * unit(rng)) * 0.25f;
                const int cell = g.locate(x, y, xr, yr);
                REQUIRE(cell == g.physical(i, j));
                g.fuse(cell, xr, yr, 100.0 + 0.5 * unit(rng), 10.0f + 100.0f * unit(rng), 0);
            }
        }
    }
}

// Turns g by angle about (px, py) with the SIMD build in use and checks every cell against
// the library's double-precision reference (EgocentricGrid::transform_reference) turning a
// copy; returns how many non-empty cells were compared.
int turn_and_compare(EgocentricGrid& g, double angle, double px, double py)
{
    EgocentricGrid reference = g;
    std::vector<uint8_t> near_edge;
    const int expected_dropped = reference.transform_reference(angle, px, py, &near_edge);
    const int dropped = g.transform(angle, px, py);
    CHECK(std::abs(dropped - expected_dropped) <= 2);
    int compared = 0;
    for (int i = 0; i < g.nx(); ++i) {
        for (int j = 0; j < g.ny(); ++j) {
            const int physical = g.physical(i, j);
            if (near_edge[static_cast<std::size_t>(physical)]) continue;
            const CellSums& e = reference.at(i, j);
            const CellSums& cell = g.at(i, j);
            INFO("angle " << angle << " cell " << i << ", " << j);
            if (e.empty()) {
                CHECK(cell.empty());
                CHECK(g.count(i, j) == 0);
                CHECK(std::isnan(g.extremes(i, j).z_max_m));
                CHECK(std::isnan(g.extremes(i, j).z_min_m));
                continue;
            }
            REQUIRE_FALSE(cell.empty());
            CHECK(g.count(i, j) == reference.count(i, j));
            CHECK(cell.w == Approx(e.w).epsilon(1e-5));
            CHECK(cell.x_wx / cell.w == Approx(e.x_wx / e.w).margin(1e-4));
            CHECK(cell.y_wy / cell.w == Approx(e.y_wy / e.w).margin(1e-4));
            CHECK(cell.x_wx2 / cell.w == Approx(e.x_wx2 / e.w).margin(1e-6));
            CHECK(cell.y_wy2 / cell.w == Approx(e.y_wy2 / e.w).margin(1e-6));
            double wz = 0, wz2 = 0, ewz = 0, ewz2 = 0;
            z_sums_about(cell, 0.0, wz, wz2);
            z_sums_about(e, 0.0, ewz, ewz2);
            CHECK(wz / cell.w == Approx(ewz / e.w).epsilon(1e-6));
            const CellStatistics stats = cell_statistics(cell, StatisticsKind::variance_weighted);
            const CellStatistics expected = cell_statistics(e, StatisticsKind::variance_weighted);
            CHECK(stats.variance_z_m2 == Approx(expected.variance_z_m2).margin(1e-5));
            // Max of maxes, min of mins: exact, whatever the order of the merges.
            CHECK(g.extremes(i, j).z_max_m == reference.extremes(i, j).z_max_m);
            CHECK(g.extremes(i, j).z_min_m == reference.extremes(i, j).z_min_m);
            ++compared;
        }
    }
    return compared;
}

}  // namespace

TEST_CASE("transform pools every cell where its samples land, rotation after rotation, and leaves the rest empty")
{
    // Both builds of the rotation's arithmetic (simd.hpp), where the CPU runs them.
    const SimdLevel level = GENERATE(SimdLevel::generic, SimdLevel::avx2);
    if (!cpu_runs(level)) return;
    const ScopedSimdLevel use(level);
    INFO("simd level " << to_string(level));
    // 37 columns: not a whole number of groups of four. Random heights and remainders, some
    // cells empty, the ring index not zero.
    EgocentricGrid g(41, 37, 0.25);
    std::mt19937 rng(7);
    g.wrap_forward(13);
    fuse_random(g, rng, 0.3f);
    // The frame turns about a point near its origin, there and back, so that most cells stay.
    const double turns[][3] = {{0.087, 0.1, -0.4}, {-0.2, 0.0, 0.3}, {0.3, -0.1, 0.0}, {0.087, 0.2, 0.2}, {-0.25, -0.2, -0.1}};
    for (const auto& turn : turns) CHECK(turn_and_compare(g, turn[0], turn[1], turn[2]) > 300);
}

// A rotation frees slots twice over: those of the cells turned out of the map and those of
// the cells merged into another. New cells then take them: none may take a slot still in
// use, and none may be lost.
TEST_CASE("after a rotation that drops and merges cells, new cells take only free slots")
{
    const SimdLevel level = GENERATE(SimdLevel::generic, SimdLevel::avx2);
    if (!cpu_runs(level)) return;
    const ScopedSimdLevel use(level);
    INFO("simd level " << to_string(level));
    EgocentricGrid g(41, 37, 0.25);
    std::mt19937 rng(13);
    fuse_random(g, rng, 0.3f);
    // A small turn: fewer slots freed than would make the pool compact itself (a quarter).
    const int known_before = g.known_cells();
    const int dropped = g.transform(0.087, 0.1, -0.2);
    const int known_after = g.known_cells();
    REQUIRE(dropped > 10);
    REQUIRE(known_before - dropped - known_after > 5);  // merged into another cell
    REQUIRE((known_before - known_after) * 4 < known_before);
    std::vector<CellSums> kept(static_cast<std::size_t>(41 * 37));
    std::vector<uint32_t> kept_n(kept.size());
    int known = 0;
    for (int cell = 0; cell < 41 * 37; ++cell) {
        kept[static_cast<std::size_t>(cell)] = g.at(cell);
        kept_n[static_cast<std::size_t>(cell)] = g.count(cell);
        known += g.at(cell).empty() ? 0 : 1;
    }
    CHECK(known == known_after);
    // One sample into every empty cell: they take the freed slots, then new ones.
    int added = 0;
    for (int cell = 0; cell < 41 * 37; ++cell) {
        if (!kept[static_cast<std::size_t>(cell)].empty()) continue;
        g.fuse(cell, 0.01f, -0.02f, 50.0 + 0.01 * cell, 2.0f, 0);  // a height of its own
        ++added;
    }
    REQUIRE(added > known_before - known_after);
    CHECK(g.known_cells() == known_after + added);
    for (int cell = 0; cell < 41 * 37; ++cell) {
        INFO("cell " << cell);
        const CellSums& now = g.at(cell);
        if (kept[static_cast<std::size_t>(cell)].empty()) {
            CHECK(g.count(cell) == 1);
            CHECK(now.w == 2.0f);
            CHECK(now.z_ref_m == static_cast<float>(50.0 + 0.01 * cell));
            continue;
        }
        CHECK(g.count(cell) == kept_n[static_cast<std::size_t>(cell)]);
        CHECK(now.w == kept[static_cast<std::size_t>(cell)].w);
        CHECK(now.x_wx == kept[static_cast<std::size_t>(cell)].x_wx);
        CHECK(now.z_ref_m == kept[static_cast<std::size_t>(cell)].z_ref_m);
        CHECK(now.z_wz2 == kept[static_cast<std::size_t>(cell)].z_wz2);
    }
}

// Between rotations, wraps free slots of the pool, new samples take free slots or new ones,
// and a clear empties it: each rotation must still find every known cell, and only those.
TEST_CASE("the cells nothing lands on are empty when wraps, new samples and a clear come between rotations")
{
    const SimdLevel level = GENERATE(SimdLevel::generic, SimdLevel::avx2);
    if (!cpu_runs(level)) return;
    const ScopedSimdLevel use(level);
    const int columns = GENERATE(37, 67);
    INFO("simd level " << to_string(level) << ", " << columns << " columns");
    EgocentricGrid g(41, columns, 0.25);  // 10.25 m long: a cell moves up to 6 cells at 0.3 rad
    std::mt19937 rng(11);
    fuse_random(g, rng, 0.3f);
    CHECK(turn_and_compare(g, 0.087, 0.1, -0.2) > 300);
    g.wrap_forward(4);
    fuse_random(g, rng, 0.8f);  // new samples in a fifth of the cells, known or not
    CHECK(turn_and_compare(g, -0.15, 0.0, 0.1) > 300);
    g.wrap_backward(2);
    CHECK(turn_and_compare(g, 0.3, -0.1, 0.0) > 200);
    g.clear();
    CHECK(turn_and_compare(g, 0.1, 0.0, 0.0) == 0);  // every cell checked empty
    fuse_random(g, rng, 0.9f);
    CHECK(turn_and_compare(g, -0.087, 0.2, 0.1) > 50);
    CHECK(turn_and_compare(g, 0.2, 0.0, -0.3) > 50);
}

// A row shorter than a group of cells the rotation turns at once: a cell's row and column
// come from its index, which must hold for any row length.
TEST_CASE("a map narrower than 16 columns turns like a wide one")
{
    const SimdLevel level = GENERATE(SimdLevel::generic, SimdLevel::avx2);
    if (!cpu_runs(level)) return;
    const ScopedSimdLevel use(level);
    const int columns = GENERATE(5, 9);
    INFO("simd level " << to_string(level) << ", " << columns << " columns");
    EgocentricGrid g(40, columns, 0.25);
    std::mt19937 rng(5);
    fuse_random(g, rng, 0.2f);
    // Small turns about the strip's rear edge (the frame's origin), there and back, so that
    // most cells stay on it.
    int compared = 0;
    for (const double angle : {0.005, -0.01, 0.008, -0.004}) compared += turn_and_compare(g, angle, 0.0, 0.0);
    CHECK(compared > 40 * columns);
}

TEST_CASE("a cell's extremes are the highest and lowest sample fused into it, NaN while it is empty")
{
    EgocentricGrid g(10, 4, 1.0);
    CHECK(std::isnan(g.extremes(3, 1).z_max_m));
    CHECK(std::isnan(g.extremes(3, 1).z_min_m));
    for (const double z : {101.25, 99.5, 100.75}) put(g, 3.5f, -0.5f, z);
    CHECK(g.extremes(3, 1).z_max_m == 101.25f);
    CHECK(g.extremes(3, 1).z_min_m == 99.5f);
    CHECK(std::isnan(g.extremes(3, 2).z_max_m));  // the neighbour stays unknown
    // A single sample is both.
    put(g, 5.5f, 0.5f, -2.0);
    CHECK(g.extremes(5, 2).z_max_m == -2.0f);
    CHECK(g.extremes(5, 2).z_min_m == -2.0f);
}

TEST_CASE("a wrap keeps the extremes of the rows it keeps and clears those of the rows it recycles")
{
    EgocentricGrid g(10, 4, 1.0);
    for (int i = 0; i < 10; ++i) {
        put(g, static_cast<float>(i) + 0.5f, 0.5f, i);
        put(g, static_cast<float>(i) + 0.5f, 0.5f, i + 0.5);
    }
    g.wrap_forward(3);
    for (int i = 0; i < 7; ++i) {
        CHECK(g.extremes(i, 2).z_max_m == static_cast<float>(i + 3.5));
        CHECK(g.extremes(i, 2).z_min_m == static_cast<float>(i + 3));
    }
    for (int i = 7; i < 10; ++i) CHECK(std::isnan(g.extremes(i, 2).z_max_m));
    // A recycled row's first sample starts afresh (the old row 0 held 0 and 0.5).
    put(g, 8.5f, 0.5f, 42.0);
    CHECK(g.extremes(8, 2).z_max_m == 42.0f);
    CHECK(g.extremes(8, 2).z_min_m == 42.0f);
    g.wrap_backward(2);
    CHECK(std::isnan(g.extremes(0, 2).z_min_m));
    CHECK(g.extremes(2, 2).z_max_m == 3.5f);
}

// The reference rotation itself, by hand, and the kernels on the same map: a shift of the
// frame by half a cell sideways lands two neighbours in one cell and turns one out.
TEST_CASE("a rotation merges cells landing together (max of maxes, min of mins) and drops those turned out")
{
    EgocentricGrid g(10, 10, 1.0);  // x 0..10, y -5..5
    put(g, 4.9f, 0.95f, 10.0);      // cell (4, 5)
    put(g, 4.9f, 0.95f, 12.0);
    put(g, 4.9f, 1.05f, 7.0);       // cell (4, 6)
    put(g, 9.5f, -4.7f, 3.0);       // cell (9, 0)
    // The frame's origin moves 0.5 m to the left: y 0.95 -> 0.45 and 1.05 -> 0.55, both in
    // column 5 (y 0..1, centre 0.5); y -4.7 -> -5.2, outside.
    const auto check = [](EgocentricGrid& turned, int dropped) {
        CHECK(dropped == 1);
        CHECK(turned.known_cells() == 1);
        CHECK(turned.count(4, 5) == 3);
        const CellSums& c = turned.at(4, 5);
        CHECK(c.w == 3.0f);
        CHECK(c.x_wx == Approx(3 * 0.4).margin(1e-5));       // x 4.9 from the centre 4.5
        CHECK(c.y_wy == Approx(-0.05).margin(1e-5));         // y_rel -0.05, -0.05, +0.05
        CHECK(c.y_wy2 == Approx(3 * 0.0025).margin(1e-6));
        CHECK(cell_statistics(c, StatisticsKind::variance_weighted).mean_z_m == Approx(29.0 / 3.0));
        CHECK(turned.extremes(4, 5).z_max_m == 12.0f);
        CHECK(turned.extremes(4, 5).z_min_m == 7.0f);
        CHECK(std::isnan(turned.extremes(4, 6).z_max_m));
        CHECK(std::isnan(turned.extremes(9, 0).z_min_m));
    };
    EgocentricGrid reference = g;
    check(reference, reference.transform_reference(0.0, 0.0, 0.5));
    for (const SimdLevel level : {SimdLevel::generic, SimdLevel::avx2}) {
        if (!cpu_runs(level)) continue;
        const ScopedSimdLevel use(level);
        INFO("simd level " << to_string(level));
        EgocentricGrid turned = g;
        check(turned, turned.transform(0.0, 0.0, 0.5));
        // A cell turned out of the map loses its extremes: the slot a new cell takes starts afresh.
        put(turned, 9.5f, -4.7f, 1.0);
        CHECK(turned.extremes(9, 0).z_max_m == 1.0f);
        CHECK(turned.extremes(9, 0).z_min_m == 1.0f);
    }
}

// Cells that land together in a rotation keep the newest of their times. Each cell's one
// sample has a time and a height equal to it, so after the merge a cell's newest time must
// be its highest sample.
TEST_CASE("a rotation's merged cells keep the newest time of those merged")
{
    const SimdLevel level = GENERATE(SimdLevel::generic, SimdLevel::avx2);
    if (!cpu_runs(level)) return;
    const ScopedSimdLevel use(level);
    INFO("simd level " << to_string(level));
    EgocentricGrid g(41, 37, 0.25);
    std::mt19937 rng(5);
    std::vector<TimeTick> times(41 * 37);
    std::iota(times.begin(), times.end(), TimeTick{-600});  // negative times count too
    std::shuffle(times.begin(), times.end(), rng);
    for (int cell = 0; cell < 41 * 37; ++cell) {
        const TimeTick t = times[static_cast<std::size_t>(cell)];
        g.fuse(cell, 0.01f, 0.02f, static_cast<double>(t), 1.0f, t);
    }
    g.transform(0.087, 0.1, -0.2);
    int merged = 0;
    for (int cell = 0; cell < 41 * 37; ++cell) {
        const CellTally& t = g.tally(cell);
        if (t.count == 0) {
            CHECK(t.newest_ms == kNoTime);
            continue;
        }
        INFO("cell " << cell);
        merged += t.count > 1 ? 1 : 0;
        CHECK(t.newest_ms == static_cast<TimeTick>(t.extremes.z_max_m));
    }
    CHECK(merged > 5);
}

namespace {

// Cell for cell, in unwrapped order: a map moved sideways by the column ring (shifted)
// against the same map moved by the full transform (moved). The transform rewrites only
// the x and y sums, in float about the new centre; everything else must be the same bits.
// Returns the number of known cells.
int compare_shifted(const EgocentricGrid& shifted, const EgocentricGrid& moved)
{
    int known = 0;
    for (int i = 0; i < moved.nx(); ++i) {
        for (int j = 0; j < moved.ny(); ++j) {
            INFO("cell " << i << ", " << j);
            const CellSums& e = moved.at(i, j);
            const CellSums& a = shifted.at(i, j);
            REQUIRE(a.empty() == e.empty());
            CHECK(shifted.count(i, j) == moved.count(i, j));
            CHECK(shifted.tally(i, j).newest_ms == moved.tally(i, j).newest_ms);
            if (e.empty()) {
                CHECK(std::isnan(shifted.extremes(i, j).z_max_m));
                continue;
            }
            ++known;
            CHECK(shifted.extremes(i, j).z_max_m == moved.extremes(i, j).z_max_m);
            CHECK(shifted.extremes(i, j).z_min_m == moved.extremes(i, j).z_min_m);
            CHECK(a.w == e.w);
            CHECK(a.z_wz == e.z_wz);
            CHECK(a.z_ref_m == e.z_ref_m);
            CHECK(a.z_wz2 == e.z_wz2);
            CHECK(a.x_wx == Approx(e.x_wx).margin(1e-5 * e.w));
            CHECK(a.y_wy == Approx(e.y_wy).margin(1e-5 * e.w));
            CHECK(a.x_wx2 == Approx(e.x_wx2).margin(1e-6 * e.w));
            CHECK(a.y_wy2 == Approx(e.y_wy2).margin(1e-6 * e.w));
        }
    }
    CHECK(shifted.known_cells() == known);
    return known;
}

}  // namespace

// The sideways re-centre is a ring index in Y as the wrap is in X: shift_columns must give
// the map that transform(0, 0, columns G) gives, the columns that leave cleared and reused
// on the other side, and every reader (locate, physical, the rotation's kernels and its
// reference) must follow the column index.
TEST_CASE("a sideways move by the column ring gives the full transform's map, cell for cell")
{
    const SimdLevel level = GENERATE(SimdLevel::generic, SimdLevel::avx2);
    if (!cpu_runs(level)) return;
    const ScopedSimdLevel use(level);
    INFO("simd level " << to_string(level));
    const double g_m = 0.25;
    EgocentricGrid shifted(41, 37, g_m);
    std::mt19937 rng(17);
    shifted.wrap_forward(13);  // the row ring not at zero either
    fuse_random(shifted, rng, 0.2f);
    EgocentricGrid moved = shifted;
    // Left, right, by several, by more than half the map, and by all of it.
    int m_j = 0;
    for (const int columns : {1, -1, 3, -5, 1, 20, -2, 37}) {
        INFO("shift by " << columns << " columns");
        const int cleared = shifted.shift_columns(columns);
        const int dropped = moved.transform(0.0, 0.0, columns * g_m);
        CHECK(cleared == dropped);
        m_j = ((m_j + columns) % 37 + 37) % 37;
        CHECK(shifted.column_index() == m_j);
        CHECK(moved.column_index() == 0);
        compare_shifted(shifted, moved);
        // The columns that came in are empty, and the next samples land in them through
        // locate() in both maps alike.
        const int first_new = columns > 0 ? 37 - columns : 0;
        for (int i = 0; i < 41; ++i)
            for (int j = first_new; j < first_new + std::min(std::abs(columns), 37); ++j)
                CHECK(shifted.count(i, j) == 0);
        std::mt19937 same_a(static_cast<unsigned>(100 + columns)), same_b = same_a;
        fuse_random(shifted, same_a, 0.7f);
        fuse_random(moved, same_b, 0.7f);
        CHECK(compare_shifted(shifted, moved) > 200);
    }
    // A rotation after the column ring moved: the kernels read each cell's column through
    // m_j (turn_and_compare holds them to the reference rotation on a copy).
    REQUIRE(shifted.shift_columns(4) > 0);
    REQUIRE(shifted.column_index() != 0);
    CHECK(turn_and_compare(shifted, 0.087, 0.1, -0.2) > 300);
    CHECK(shifted.column_index() == 0);
    fuse_random(shifted, rng, 0.5f);  // the far columns, empty since the last shift, too
    REQUIRE(shifted.shift_columns(-3) > 0);
    CHECK(turn_and_compare(shifted, -0.15, 0.0, 0.1) > 300);
    // A wrap after a column shift clears whole unwrapped rows, whatever m_j.
    fuse_random(shifted, rng, 0.5f);
    REQUIRE(shifted.shift_columns(2) > 0);
    // Samples in the columns that just came in too: a wrap that took a physical row to
    // start at physical(i, 0) would leave them and clear the next row's instead.
    fuse_random(shifted, rng, 0.0f);
    for (int j = 35; j < 37; ++j) REQUIRE(shifted.count(40, j) > 0);
    moved = shifted;
    shifted.wrap_forward(3);
    for (int i = 38; i < 41; ++i)
        for (int j = 0; j < 37; ++j) CHECK(shifted.count(i, j) == 0);
    for (int i = 0; i < 38; ++i)
        for (int j = 0; j < 37; ++j) CHECK(shifted.count(i, j) == moved.count(i + 3, j));
}
