// The candidate arcs: where a box blocks them, what they sweep, against the plain
// definition (first_cover_s).
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "ugv_test/terrain_grid_builder.hpp"
#include "ugv/traverse/candidate_arcs.hpp"

using namespace ugv::traverse;
using namespace ugv::traverse::test;

namespace {

struct Judged
{
    std::vector<ArcVerdict> arcs;
    int best = -1;
};

Judged judge(const TerrainGrid& g, const ArcSetConfig& ac = ArcSetConfig{})
{
    CellClassifier cls{ClassifierConfig{}};
    TraversabilityLayers l;
    cls.classify(g, Odometer{}, l);
    CandidateArcs arcs(ac, Footprint{}, g.resolution_m);
    Judged j;
    arcs.judge(g, l, j.arcs, j.best);
    return j;
}

}  // namespace

TEST_CASE("25 arcs span the turning limits, right to left")
{
    CandidateArcs arcs(ArcSetConfig{}, Footprint{}, 0.2);
    REQUIRE(arcs.count() == 25);
    CHECK(arcs.curvature(0) == Approx(-0.2));
    CHECK(arcs.curvature(12) == Approx(0.0).margin(1e-12));
    CHECK(arcs.curvature(24) == Approx(0.2));
}

TEST_CASE("on flat ground no arc is blocked")
{
    TerrainGrid g = empty_grid();
    fill(g, [](double, double) { return 1.5; });
    const Judged j = judge(g);
    for (const ArcVerdict& v : j.arcs) {
        CHECK_FALSE(v.blocked);
        CHECK(v.clear_distance_m == Approx(12.0));
        CHECK(v.unknown_fraction < 0.01);
        CHECK(v.merit > 0.5);
    }
    CHECK(j.best >= 0);
}

TEST_CASE("a box 6 m ahead of the front bumper blocks the straight arc at 6 m")
{
    TerrainGrid g = empty_grid();
    // Front bumper at x = 2.0: the box's face at x = 8.0, 1 m wide, 0.5 m tall.
    fill(g, [](double x, double y) { return 1.5 + (x >= 8.0 && x < 9.0 && std::abs(y) < 0.5 ? 0.5 : 0.0); });
    const Judged j = judge(g);
    const ArcVerdict& straight = j.arcs[12];
    CHECK(straight.blocked);
    CHECK(std::abs(straight.clear_distance_m - 6.0) <= 0.2);
    CHECK(straight.merit < 0.51);
    // The hardest turns pass beside it.
    CHECK_FALSE(j.arcs[0].blocked);
    CHECK_FALSE(j.arcs[24].blocked);
    CHECK(j.best != 12);
    CHECK_FALSE(j.arcs[static_cast<std::size_t>(j.best)].blocked);
}

TEST_CASE("a map turned by its residual yaw is read in the body frame")
{
    // The box straight ahead in the body frame, the map axes turned by -4 degrees.
    TerrainGrid g = empty_grid();
    g.residual_yaw_rad = 4.0 * M_PI / 180.0;
    fill(g, [&](double mx, double my) {
        const double c = std::cos(g.residual_yaw_rad), s = std::sin(g.residual_yaw_rad);
        const double bx = c * mx + s * my, by = -s * mx + c * my;  // map -> body
        return 1.5 + (bx >= 8.0 && bx < 9.0 && std::abs(by) < 0.5 ? 0.5 : 0.0);
    });
    const Judged j = judge(g);
    CHECK(j.arcs[12].blocked);
    CHECK(std::abs(j.arcs[12].clear_distance_m - 6.0) <= 0.25);
}

TEST_CASE("the swept width is the configured one to within a fine cell")
{
    // Two walls two cells thick along the straight arc, the map's cells shifted across it by
    // fractions of a cell. Walls whose cells lie wholly outside the swept footprint leave the
    // arc free (when every map cell the outline grazed counted, they blocked it from up to a
    // cell and a half outside); walls whose nearest cells have their centres inside block it.
    const ArcSetConfig ac;
    const Footprint fp;
    const double half = 0.5 * fp.width_m + ac.margin_m;
    for (double shift : {0.0, 0.03, 0.05, 0.1, 0.15}) {
        for (bool reaching_in : {false, true}) {
            CAPTURE(shift, reaching_in);
            TerrainGrid g = empty_grid();
            g.origin_y_m += shift;
            const double from_y = reaching_in ? half - g.resolution_m : half + 0.5 * g.resolution_m + 1e-6;
            for (int i = 0; i < g.nx; ++i)
                for (int j = 0; j < g.ny; ++j) {
                    const double y = std::abs(cy(g, j));
                    const double z = 1.5 + (y >= from_y && y < from_y + 2 * g.resolution_m ? 1.0 : 0.0);
                    set_samples(g, i, j, {z - 0.01, z, z + 0.01, z, z - 0.005, z + 0.005});
                }
            const Judged j = judge(g, ac);
            CHECK(j.arcs[12].blocked == reaching_in);
        }
    }
}

TEST_CASE("unknown cells lower the merit, and block under the cautious policy")
{
    TerrainGrid g = empty_grid();
    fill(g, [](double, double) { return 1.5; });
    // Nothing known beyond 4 m.
    for (int i = 0; i < g.nx; ++i)
        for (int jj = 0; jj < g.ny; ++jj)
            if (cx(g, i) > 4.0) {
                const std::size_t k = static_cast<std::size_t>(i) * g.ny + jj;
                g.count[k] = 0;
                g.mean_z_m[k] = g.max_z_m[k] = g.min_z_m[k] = g.variance_z_m2[k] = NAN;
            }
    const Judged optimistic = judge(g);
    CHECK_FALSE(optimistic.arcs[12].blocked);
    CHECK(optimistic.arcs[12].unknown_fraction > 0.3);
    CHECK(optimistic.arcs[12].merit < 0.85);
    ArcSetConfig cautious;
    cautious.unknown_policy = UnknownPolicy::cautious;
    cautious.max_unknown_fraction = 0.2;
    const Judged j = judge(g, cautious);
    CHECK(j.arcs[12].blocked);
    CHECK(j.best == -1);
}

TEST_CASE("the sweep agrees with the plain definition of cover")
{
    // A swept fine cell (half the resolution) is first touched at s: its centre is covered
    // by the footprint grown by half a fine cell's diagonal by then, and not by the
    // footprint shrunk by as much before then.
    const double res = 0.2, fine = 0.5 * res, grow = 0.5 * std::sqrt(2.0) * fine + 0.01;
    const ArcSetConfig ac;
    const Footprint fp;
    const Footprint grown{fp.rear_x_m - grow, fp.front_x_m + grow, fp.width_m + 2 * grow};
    const Footprint shrunk{fp.rear_x_m + grow, fp.front_x_m - grow, fp.width_m - 2 * grow};
    CandidateArcs arcs(ac, fp, res);
    std::mt19937 rng(7);
    for (int a : {0, 5, 12, 20, 24}) {
        const auto& sweep = arcs.sweep(a);
        REQUIRE(!sweep.empty());
        std::uniform_int_distribution<std::size_t> pick(0, sweep.size() - 1);
        for (int n = 0; n < 300; ++n) {
            const auto& c = sweep[pick(rng)];
            const Eigen::Vector2d p{c.x_m, c.y_m};
            const double early = first_cover_s(arcs.curvature(a), grown, ac.margin_m, ac.length_m, p, 0.005);
            const double late = first_cover_s(arcs.curvature(a), shrunk, ac.margin_m, ac.length_m, p, 0.005);
            REQUIRE_FALSE(std::isnan(early));
            CHECK(early <= c.s_m + 0.02);
            if (!std::isnan(late)) CHECK(late >= c.s_m - 0.02);
        }
    }
}

TEST_CASE("bad arc sets are refused")
{
    ArcSetConfig c;
    c.count = 0;
    CHECK_THROWS(CandidateArcs(c, Footprint{}, 0.2));
    c = ArcSetConfig{};
    c.max_curvature_per_m = 2.0;  // a radius of 0.5 m: inside the swept width
    CHECK_THROWS(CandidateArcs(c, Footprint{}, 0.2));
    c = ArcSetConfig{};
    c.length_m = -1;
    CHECK_THROWS(CandidateArcs(c, Footprint{}, 0.2));
    Footprint f;
    f.front_x_m = -1;
    CHECK_THROWS(CandidateArcs(ArcSetConfig{}, f, 0.2));
}

TEST_CASE("the verdicts stay the same when the marks of counted cells wrap")
{
    // Each judgement marks the map cells an arc counts with the arc's 16-bit stamp, which
    // wraps after 65535 arcs. One short arc: a map judged once, then 65534 maps that lie
    // wholly outside the sweep (nothing marked), then the first again: its stamp is again
    // the value its first judgement left in the cells, which must not count as marked.
    TerrainGrid g = empty_grid(40, 40);
    fill(g, [](double x, double y) { return 1.5 + (x >= 2.4 && x < 3.0 && std::abs(y) < 0.3 ? 0.5 : 0.0); });
    for (int i = 0; i < g.nx; ++i)
        for (int j = 0; j < g.ny; ++j)
            if ((i * 7 + j * 13) % 5 == 0) {
                const std::size_t k = static_cast<std::size_t>(i) * g.ny + j;
                g.count[k] = 0;
                g.mean_z_m[k] = g.max_z_m[k] = g.min_z_m[k] = g.variance_z_m2[k] = NAN;
            }
    TerrainGrid away = g;
    away.origin_x_m = 1000.0;
    ArcSetConfig ac;
    ac.count = 1;
    ac.length_m = 1.0;
    CellClassifier cls{ClassifierConfig{}};
    TraversabilityLayers l;
    cls.classify(g, Odometer{}, l);
    const CandidateArcs arcs(ac, Footprint{}, g.resolution_m);
    Judged first, again;
    arcs.judge(g, l, first.arcs, first.best);
    for (int n = 0; n < 65534; ++n) arcs.judge(away, l, again.arcs, again.best);
    CHECK(again.arcs[0].unknown_fraction == 1.0);  // all outside
    arcs.judge(g, l, again.arcs, again.best);
    CHECK(first.arcs[0].blocked);
    CHECK(first.arcs[0].unknown_fraction > 0.0);
    CHECK(first.arcs[0].unknown_fraction < 1.0);
    CHECK(again.arcs[0].clear_distance_m == first.arcs[0].clear_distance_m);
    CHECK(again.arcs[0].unknown_fraction == first.arcs[0].unknown_fraction);
    CHECK(again.arcs[0].mean_cost == first.arcs[0].mean_cost);
}
