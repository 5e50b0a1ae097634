// ugv-render --traverse: the traversability map with its candidate arcs (figure 20) drawn
// from crafted messages, and the pairing of maps with the arcs of the same terrain map.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "traverse_pairing.hpp"
#include "traverse_render.hpp"

using namespace ugv;
using namespace ugv::render;

namespace Catch {
template <>
struct StringMaker<Rgb>
{
    static std::string convert(const Rgb& c)
    {
        return "{" + std::to_string(c.r) + ", " + std::to_string(c.g) + ", " + std::to_string(c.b) + "}";
    }
};
}  // namespace Catch

namespace {

constexpr int kPx = 3;
constexpr int kBlockedFirst = 10, kBlockedLast = 14, kBest = 16;
constexpr float kClear = 3.8f;  // the blocked arcs' body origin stops here; front bumper at 5.8 m

std::size_t cell(const traversability_map_t& m, double x, double y)
{
    const int i = static_cast<int>(std::floor((x - m.origin_x) / m.resolution));
    const int j = static_cast<int>(std::floor((y - m.origin_y) / m.resolution));
    return static_cast<std::size_t>(i * m.ny + j);
}

void cell_xy(const traversability_map_t& m, double x, double y, int& px, int& py)
{
    const std::size_t k = cell(m, x, y);
    traverse_cell_pixel(m, kPx, static_cast<int>(k) / m.ny, static_cast<int>(k) % m.ny, px, py);
    ++px;  // the middle of the cell's 3 x 3 pixels
    ++py;
}

// 16 m x 15 m of 0.1 m cells, the body origin 2.5 m from the near edge, in the middle: all
// traversable at cost 0.2, an obstacle block 6-7 m ahead (|y| < 0.5 m), a ditch 3 m ahead
// 5 m to the left, a patch of cost 0.9 to the right, and unknown beyond 9 m.
traversability_map_t flat_map()
{
    traversability_map_t m{};
    m.utime = 1'700'000'000'000'000;
    m.seq = 1;
    m.map_seq = 41;
    m.resolution = 0.1f;
    m.nx = 160;
    m.ny = 150;
    m.origin_x = -2.5f;
    m.origin_y = -7.5f;
    m.ncells = m.nx * m.ny;
    const auto n = static_cast<std::size_t>(m.ncells);
    m.cell_class.assign(n, traversability_map_t::CLASS_TRAVERSABLE);
    m.cost.assign(n, 0.2f);
    for (auto* layer : {&m.step_m, &m.drop_m, &m.slope_deg, &m.roughness_m, &m.span_m}) layer->assign(n, 0.0f);
    m.certainty.assign(n, 1.0f);
    for (double x = 6.05; x < 7.0; x += 0.1)
        for (double y = -0.45; y < 0.5; y += 0.1) m.cell_class[cell(m, x, y)] = traversability_map_t::CLASS_OBSTACLE;
    for (double x = 3.05; x < 3.5; x += 0.1)
        for (double y = 5.05; y < 5.5; y += 0.1)
            m.cell_class[cell(m, x, y)] = traversability_map_t::CLASS_NEGATIVE_OBSTACLE;
    for (double x = 0.55; x < 1.5; x += 0.1)
        for (double y = -5.45; y < -4.5; y += 0.1) m.cost[cell(m, x, y)] = 0.9f;
    for (std::size_t k = 115 * 150; k < n; ++k) {
        m.cell_class[k] = traversability_map_t::CLASS_UNKNOWN;
        m.cost[k] = NAN;
    }
    return m;
}

// 25 arcs over curvatures -0.2 .. 0.2 (right to left), 12 m long; the five middle ones
// blocked by the box at kClear, the best arc 16.
candidate_arcs_t arcs_for(const traversability_map_t& m)
{
    candidate_arcs_t a{};
    a.utime = m.utime;
    a.seq = 7;
    a.map_seq = m.map_seq;
    a.length_m = 12.0f;
    a.swept_width_m = 2.2f;
    a.narcs = 25;
    for (int k = 0; k < 25; ++k) {
        const bool blocked = k >= kBlockedFirst && k <= kBlockedLast;
        a.curvature.push_back(static_cast<float>(-0.2 + k * 0.4 / 24));
        a.clear_distance_m.push_back(blocked ? kClear : 12.0f);
        a.unknown_fraction.push_back(0.0f);
        a.mean_cost.push_back(0.2f);
        a.merit.push_back(blocked ? 0.0f : 0.8f);
        a.blocked.push_back(blocked ? 1 : 0);
    }
    a.best = kBest;
    return a;
}

bool is_arc_colour(Rgb c) { return c == kFreeArc || c == kBlockedArc || c == kBestArc; }

}  // namespace

TEST_CASE("traversability picture: class colours, the cost shading, the size")
{
    const traversability_map_t m = flat_map();
    const candidate_arcs_t a = arcs_for(m);
    TraverseOptions o;
    o.cell_px = kPx;
    const Image img = render_traverse(m, &a, o);
    CHECK(img.width() == 2 * kTraverseMargin + 150 * kPx + kLegendWidth);
    CHECK(img.height() == 2 * kTraverseMargin + 160 * kPx);
    int x = 0, y = 0;
    cell_xy(m, 6.5, 0.3, x, y);
    CHECK(img.at(x, y) == kObstacle);
    cell_xy(m, 3.2, 5.2, x, y);
    CHECK(img.at(x, y) == kNegativeObstacle);
    cell_xy(m, 13.0, 7.0, x, y);
    CHECK(img.at(x, y) == kUnknownCell);
    cell_xy(m, 1.0, -6.5, x, y);
    CHECK(img.at(x, y) == traversable_colour(0.2));
    cell_xy(m, 1.0, -5.0, x, y);
    CHECK(img.at(x, y) == traversable_colour(0.9));
    CHECK_FALSE(traversable_colour(0.2) == traversable_colour(0.9));
    // Every class, arc and the outline in its own colour.
    const std::vector<Rgb> all = {traversable_colour(0.0), traversable_colour(1.0), kObstacle, kNegativeObstacle,
                                  kUnknownCell, kFreeArc, kBlockedArc, kBestArc, kOutline};
    for (std::size_t i = 0; i < all.size(); ++i)
        for (std::size_t j = i + 1; j < all.size(); ++j) CHECK_FALSE(all[i] == all[j]);
    // Forward is up: the far cells at the top.
    traverse_cell_pixel(m, kPx, 159, 0, x, y);
    CHECK(y == kTraverseMargin);
    CHECK(x == kTraverseMargin + 149 * kPx);
}

TEST_CASE("traversability picture: free arcs solid to their end, blocked ones dashed to the hit, the best highlighted")
{
    const traversability_map_t m = flat_map();
    const candidate_arcs_t a = arcs_for(m);
    TraverseOptions o;
    o.cell_px = kPx;
    const Image img = render_traverse(m, &a, o);
    int x = 0, y = 0;
    // A free arc (3, curving right) is solid blue where it is apart from the others.
    for (double s = 6.0; s <= 8.0; s += 0.25) {
        arc_pixel(m, kPx, a.curvature[3], s, x, y);
        CHECK(img.at(x, y) == kFreeArc);
    }
    // Free arcs reach their full length, which the straight blocked arc does not.
    arc_pixel(m, kPx, a.curvature[9], 11.9, x, y);
    CHECK(img.at(x, y) == kFreeArc);
    // The straight arc (12) is blocked: between the vehicle's front and the stop its pixels
    // are the blocked colour or the map (dashes), never the free colour; beyond the hit,
    // nothing is drawn.
    int blocked_px = 0, gaps = 0;
    for (double s = 2.5; s <= kClear; s += 0.02) {
        arc_pixel(m, kPx, a.curvature[12], s, x, y);
        const Rgb c = img.at(x, y);
        CHECK_FALSE(c == kFreeArc);
        blocked_px += c == kBlockedArc;
        gaps += c == traversable_colour(0.2);
    }
    CHECK(blocked_px > 20);
    CHECK(gaps > 10);
    for (double s = 7.2; s <= 12.0; s += 0.1) {
        arc_pixel(m, kPx, a.curvature[12], s, x, y);
        CHECK_FALSE(is_arc_colour(img.at(x, y)));
    }
    // The cross at the front bumper when the vehicle stops: 3.8 + 2.0 m ahead.
    arc_pixel(m, kPx, 0.0, kClear + o.vehicle_front_x_m, x, y);
    CHECK(img.at(x, y) == kBlockedArc);
    // The best arc (16) is drawn wide in its own colour.
    for (double s = 6.0; s <= 10.0; s += 1.0) {
        arc_pixel(m, kPx, a.curvature[kBest], s, x, y);
        CHECK(img.at(x, y) == kBestArc);
        CHECK(img.at(x + 1, y) == kBestArc);
    }
    // The vehicle's outline: its front edge 2 m ahead of the body origin.
    int ox = 0, oy = 0;
    arc_pixel(m, kPx, 0.0, 0.0, ox, oy);
    CHECK(img.at(ox, oy) == kOutline);
    arc_pixel(m, kPx, 0.0, o.vehicle_front_x_m, x, y);
    CHECK(img.at(x + 7 * kPx, y) == kOutline);  // 0.7 m right of the centre line, on the front edge
}

TEST_CASE("traversability picture: the arcs turn with the map's residual yaw")
{
    traversability_map_t m = flat_map();
    m.residual_yaw = 0.3f;  // the body is turned 0.3 rad left of the map's axes
    candidate_arcs_t a = arcs_for(m);
    for (auto& b : a.blocked) b = 0;
    for (auto& c : a.clear_distance_m) c = 12.0f;
    TraverseOptions o;
    o.cell_px = kPx;
    const Image img = render_traverse(m, &a, o);
    // The straight arc at 8 m: map (8 cos 0.3, 8 sin 0.3) = (7.643, 2.364); pixel column
    // 10 + floor((7.5 - 2.364) / 0.1 * 3) = 164, row 10 + floor((13.5 - 7.643) / 0.1 * 3) = 185.
    int x = 0, y = 0;
    arc_pixel(m, kPx, 0.0, 8.0, x, y);
    CHECK(x == 164);
    CHECK(y == 185);
    CHECK(is_arc_colour(img.at(x, y)));
}

TEST_CASE("traversability picture: the legend is there, with or without arcs")
{
    const traversability_map_t m = flat_map();
    const candidate_arcs_t a = arcs_for(m);
    TraverseOptions o;
    o.cell_px = kPx;
    for (const candidate_arcs_t* arcs : {&a, static_cast<const candidate_arcs_t*>(nullptr)}) {
        const Image img = render_traverse(m, arcs, o);
        const int legend_x = kTraverseMargin + 150 * kPx + 2;
        auto in_legend = [&](Rgb c) {
            for (int y = 0; y < img.height(); ++y)
                for (int x = legend_x; x < img.width(); ++x)
                    if (img.at(x, y) == c) return true;
            return false;
        };
        for (Rgb c : {kTraversableEasy, kTraversableHard, kObstacle, kNegativeObstacle, kUnknownCell, kFreeArc,
                      kBlockedArc, kBestArc, kOutline})
            CHECK(in_legend(c));
    }
    // Without arcs the legend says so: its status lines differ.
    const Image with = render_traverse(m, &a, o), without = render_traverse(m, nullptr, o);
    int differ = 0;
    for (int y = 0; y < with.height(); ++y)
        for (int x = kTraverseMargin + 150 * kPx + 2; x < with.width(); ++x) differ += !(with.at(x, y) == without.at(x, y));
    CHECK(differ > 50);
}

TEST_CASE("traversability picture: arcs of another terrain map are not drawn on it")
{
    const traversability_map_t m = flat_map();
    candidate_arcs_t other = arcs_for(m);
    other.map_seq = m.map_seq - 1;
    TraverseOptions o;
    o.cell_px = kPx;
    const Image without = render_traverse(m, nullptr, o);
    CHECK(render_traverse(m, &other, o).rgb() == without.rgb());
    other.map_seq = m.map_seq;
    other.utime = m.utime - 500'000;  // the same seq from a restarted ugv-terrain
    CHECK(render_traverse(m, &other, o).rgb() == without.rgb());
    const candidate_arcs_t own = arcs_for(m);
    CHECK_FALSE(render_traverse(m, &own, o).rgb() == without.rgb());
}

TEST_CASE("traversability picture: messages whose sizes disagree are not drawn")
{
    traversability_map_t m = flat_map();
    CHECK(drawable(m));
    m.ncells -= 1;
    CHECK_FALSE(drawable(m));
    m = flat_map();
    m.cost.pop_back();
    CHECK_FALSE(drawable(m));
    m = flat_map();
    m.resolution = NAN;
    CHECK_FALSE(drawable(m));
    m = flat_map();
    m.resolution = 1e-40f;
    CHECK_FALSE(drawable(m));
    m = flat_map();
    candidate_arcs_t a = arcs_for(m);
    CHECK(drawable(a));
    // Extreme but consistent arcs are drawn within bounds: a huge length, a NaN clear
    // distance, an infinite curvature (that arc left out).
    a.length_m = 1e30f;
    a.clear_distance_m[0] = NAN;
    a.curvature[1] = INFINITY;
    a.curvature[2] = 1e30f;
    CHECK(drawable(a));
    TraverseOptions huge;
    huge.cell_px = 20;
    CHECK(render_traverse(m, &a, huge).width() == 2 * kTraverseMargin + 150 * 20 + kLegendWidth);
    a = arcs_for(m);
    a.best = 25;
    CHECK_FALSE(drawable(a));
    a = arcs_for(m);
    a.blocked.pop_back();
    CHECK_FALSE(drawable(a));
    a = arcs_for(m);
    a.length_m = -1.0f;
    CHECK_FALSE(drawable(a));
    // Drawn anyway (an empty picture, never a crash): render_traverse is safe on its own.
    m.nx = -3;
    const Image img = render_traverse(m, &a, TraverseOptions{});
    CHECK(img.width() > 0);
}

TEST_CASE("pairing: each map with the arcs of its terrain map, whichever comes first")
{
    struct Drawn
    {
        int index;
        int64_t map_seq;
        bool with_arcs;
    };
    std::vector<Drawn> drawn;
    auto record = [&](const traversability_map_t& m, const candidate_arcs_t* a, int index) {
        if (a) CHECK(same_terrain_map(m, *a));
        drawn.push_back({index, m.map_seq, a != nullptr});
        return true;
    };
    auto map_of = [](int64_t seq) {
        traversability_map_t m{};
        m.map_seq = seq;
        m.utime = 1000 * seq;
        return m;
    };
    auto arcs_of = [](int64_t seq) {
        candidate_arcs_t a{};
        a.map_seq = seq;
        a.utime = 1000 * seq;
        return a;
    };

    SECTION("the last map, its arcs after it")
    {
        TraversePairing p(0, record);
        p.add_map(map_of(4));
        p.add_arcs(arcs_of(4));
        p.add_map(map_of(5));
        p.add_arcs(arcs_of(5));
        CHECK(drawn.empty());
        p.finish();
        REQUIRE(drawn.size() == 1);
        CHECK(drawn[0].map_seq == 5);
        CHECK(drawn[0].with_arcs);
        CHECK(drawn[0].index == 2);
    }
    SECTION("the last map, its arcs before it")
    {
        TraversePairing p(0, record);
        p.add_arcs(arcs_of(5));
        p.add_map(map_of(5));
        p.finish();
        REQUIRE(drawn.size() == 1);
        CHECK(drawn[0].with_arcs);
    }
    SECTION("arcs of another map_seq, or of the same seq at another time, are not combined")
    {
        TraversePairing p(0, record);
        p.add_map(map_of(5));
        p.add_arcs(arcs_of(4));
        candidate_arcs_t late = arcs_of(5);
        late.utime += 1;
        p.add_arcs(late);
        p.finish();
        REQUIRE(drawn.size() == 1);
        CHECK_FALSE(drawn[0].with_arcs);
        CHECK(p.drawn_without_arcs() == 1);
    }
    SECTION("every 2nd map; one without arcs is drawn once kWaitMaps more maps have come")
    {
        TraversePairing p(2, record);
        for (int seq = 1; seq <= 10; ++seq) {
            p.add_map(map_of(seq));
            if (seq != 3) p.add_arcs(arcs_of(seq));
        }
        // Maps 5 and 7 are drawn as their arcs come; map 3 waits for maps 4 .. 7, then is
        // drawn without arcs when map 8 comes.
        p.finish();
        REQUIRE(drawn.size() == 5);
        const int order[5] = {1, 5, 7, 3, 9};
        for (std::size_t k = 0; k < 5; ++k) {
            CHECK(drawn[k].index == order[k]);
            CHECK(drawn[k].map_seq == order[k]);
            CHECK(drawn[k].with_arcs == (order[k] != 3));
        }
        CHECK(p.maps() == 10);
        CHECK(p.arcs() == 9);
        CHECK(p.drawn_with_arcs() == 4);
        CHECK(p.drawn_without_arcs() == 1);
    }
    SECTION("a drawing that fails stops the pairing")
    {
        TraversePairing p(1, [](const traversability_map_t&, const candidate_arcs_t*, int) { return false; });
        p.add_map(map_of(1));
        CHECK_FALSE(p.add_arcs(arcs_of(1)));
    }
}
