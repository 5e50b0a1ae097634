// One whole update (every layer, the arcs' verdicts, the counters) against a plain
// classifier and judge assembled from the documented rules and the reference parts
// (local_ground_reference, slope_reference_deg, the arcs' swept cells looked up one by one).
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <cstring>
#include <set>

#include "traverse_maps.hpp"
#include "ugv/traverse/traversability.hpp"

using namespace ugv::traverse;
using namespace ugv::traverse::test;

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

// Section 1, steps 1-6 (docs/traverse.md) cell by cell. The slope is the update's own
// (checked against slope_reference_deg within a tolerance: the fast sums are in float), so
// that the classes and costs compare exactly.
TraversabilityLayers plain_layers(const TerrainGrid& g, const ClassifierConfig& c, const std::vector<float>& slope_deg)
{
    const int nx = g.nx, ny = g.ny;
    const std::size_t n = g.cells();
    TraversabilityLayers l;
    l.reset(nx, ny);
    std::vector<float> top(n, kNaN), bottom(n, kNaN);
    for (std::size_t k = 0; k < n; ++k) {
        if (g.count[k] <= 0 || !std::isfinite(g.mean_z_m[k])) continue;
        if (g.count[k] >= 2 && g.max_z_m[k] == g.min_z_m[k] && g.max_z_m[k] == g.mean_z_m[k]) continue;
        const double age = std::isfinite(g.age_s[k]) ? g.age_s[k] : 0.0;
        const double certainty = std::max(0.0, 1.0 - age / c.max_age_s);  // nothing driven: one map
        l.certainty[k] = static_cast<float>(certainty);
        if (certainty <= 0.0) continue;
        const float var = std::isfinite(g.variance_z_m2[k]) ? g.variance_z_m2[k] : 0.0f;
        top[k] = supported(g.mean_z_m[k], g.max_z_m[k], var, g.count[k], c.min_support_samples);
        bottom[k] = supported(g.mean_z_m[k], g.min_z_m[k], var, g.count[k], c.min_support_samples);
        l.roughness_m[k] = std::sqrt(var);
        l.span_m[k] = g.max_z_m[k] - g.min_z_m[k];
    }
    auto at = [&](int i, int j) { return static_cast<std::size_t>(i) * ny + j; };
    auto window = [&](int i, int j, int h, auto&& visit) {
        for (int p = std::max(0, i - h); p <= std::min(nx - 1, i + h); ++p)
            for (int q = std::max(0, j - h); q <= std::min(ny - 1, j + h); ++q) visit(at(p, q));
    };
    const int hs = std::max(1, static_cast<int>(std::floor(c.step_radius_m / g.resolution_m + 1e-6)));
    std::vector<uint8_t> known(n), high(n), low(n);
    for (std::size_t k = 0; k < n; ++k) known[k] = std::isnan(top[k]) ? 0 : 1;
    std::vector<float> ground;
    const TerrainGrid levels = ground_levels(g, known, c.min_support_samples);
    local_ground_reference(levels, known, ground_points(g, known, c.min_support_samples, c.max_step_m),
                           c.ground_radius_m, c.max_step_m, ground);
    l.ground_m = ground;
    std::vector<float> lowest_mean(n, kNaN);
    for (int i = 0; i < nx; ++i)
        for (int j = 0; j < ny; ++j) {
            const std::size_t k = at(i, j);
            if (!known[k]) continue;
            float lowest = INFINITY, highest = -INFINITY, lowest_m = INFINITY;
            window(i, j, hs, [&](std::size_t m) {
                if (!known[m]) return;
                lowest = std::min(lowest, bottom[m]);
                highest = std::max(highest, g.mean_z_m[m]);
                lowest_m = std::min(lowest_m, levels.mean_z_m[m]);
            });
            l.step_m[k] = std::max(0.0f, top[k] - lowest);
            l.drop_m[k] = std::max(0.0f, highest - bottom[k]);
            lowest_mean[k] = lowest_m;
            if (std::isnan(ground[k])) continue;
            // Also a face within the cell: top and bottom max_step apart, the mean off the
            // ground on the side of the farther extreme.
            const double up = top[k] - ground[k], down = ground[k] - bottom[k], off = g.mean_z_m[k] - ground[k];
            const bool within = top[k] - bottom[k] >= c.max_step_m;
            high[k] = up >= c.max_step_m || (within && up >= down && off >= c.face_mean_step_m);
            low[k] = down >= c.max_drop_m || (within && down > up && -off >= c.face_mean_step_m);
        }
    // Vertical faces: an obstacle, or with a drop below the local ground beside it (before
    // any face is marked) a ditch's wall, its cell a negative obstacle if its own top and
    // bottom lie face_mean_step apart.
    std::vector<uint8_t> rim(n, 0);
    for (int i = 0; i < nx; ++i)
        for (int j = 0; j < ny; ++j) {
            const std::size_t k = at(i, j);
            if (!known[k] || l.step_m[k] < c.max_step_m || g.mean_z_m[k] - lowest_mean[k] < c.face_mean_step_m) continue;
            bool drop_beside = false;
            window(i, j, hs, [&](std::size_t m) { drop_beside = drop_beside || low[m]; });
            if (!drop_beside)
                high[k] = 1;
            else if (top[k] - bottom[k] >= c.face_mean_step_m)
                rim[k] = 1;
        }
    for (std::size_t k = 0; k < n; ++k) low[k] = low[k] || rim[k];
    // Drops across unknown cells: a known cell not high whose bottom stands max_drop over the
    // top of a known cell 2 or more cells away within shadow_radius, and more steeply than
    // max_slope over the distance between their centres, every cell the segment between the
    // centres crosses unknown.
    const int hd = std::max(1, static_cast<int>(std::floor(c.shadow_radius_m / g.resolution_m + 1e-6)));
    const double tan_slope = std::tan(c.max_slope_deg * M_PI / 180.0);
    for (int i = 0; i < nx; ++i)
        for (int j = 0; j < ny; ++j) {
            const std::size_t k = at(i, j);
            if (!known[k] || high[k]) continue;
            for (int di = -hd; di <= hd; ++di)
                for (int dj = -hd; dj <= hd; ++dj) {
                    const int ti = i + di, tj = j + dj;
                    const double d = std::hypot(di, dj) * g.resolution_m;
                    if (std::max(std::abs(di), std::abs(dj)) < 2 || d > c.shadow_radius_m + 1e-6) continue;
                    if (ti < 0 || tj < 0 || ti >= nx || tj >= ny || !known[at(ti, tj)]) continue;
                    const double drop = static_cast<double>(bottom[k]) - top[at(ti, tj)];
                    if (drop < c.max_drop_m || drop < tan_slope * d) continue;
                    bool unseen = true;
                    for (int s = 0; s < 256 && unseen; ++s) {
                        const double t = (s + 0.5) / 256;
                        const int p = i + static_cast<int>(std::lround(t * di)), q = j + static_cast<int>(std::lround(t * dj));
                        if ((p == i && q == j) || (p == ti && q == tj)) continue;
                        unseen = p >= 0 && q >= 0 && p < nx && q < ny && !known[at(p, q)];
                    }
                    if (!unseen) continue;
                    low[k] = 1;
                    l.drop_m[k] = std::max(l.drop_m[k], static_cast<float>(drop));
                }
        }
    for (int i = 0; i < nx; ++i)
        for (int j = 0; j < ny; ++j) {
            const std::size_t k = at(i, j);
            if (!known[k]) continue;
            int high_beside = 0, low_beside = 0;
            window(i, j, 2, [&](std::size_t m) {
                high_beside += m != k && high[m];
                low_beside += m != k && low[m];
            });
            const bool few = g.count[k] < c.min_support_samples;
            CellClass cls = CellClass::traversable;
            if (high[k] && !(few && high_beside == 0))
                cls = CellClass::obstacle;
            else if (low[k] && !(few && low_beside == 0))
                cls = CellClass::negative_obstacle;
            l.cell_class[k] = cls;
        }
    const int hp = std::max(1, static_cast<int>(std::floor(c.slope_radius_m / g.resolution_m + 1e-6)));
    std::vector<uint8_t> counted(n);
    for (std::size_t k = 0; k < n; ++k) counted[k] = known[k] && l.cell_class[k] == CellClass::traversable;
    for (int i = 0; i < nx; ++i)
        for (int j = 0; j < ny; ++j) {
            const std::size_t k = at(i, j);
            if (!known[k]) continue;
            const double ref = slope_reference_deg(g, counted, i, j, hp);
            INFO("slope at cell " << i << ", " << j);
            REQUIRE(std::isnan(ref) == std::isnan(slope_deg[k]));
            if (!std::isnan(ref)) CHECK(std::abs(ref - slope_deg[k]) < 0.05);
            l.slope_deg[k] = slope_deg[k];
            bool obstacle_near = false;
            window(i, j, hp, [&](std::size_t m) { obstacle_near = obstacle_near || (known[m] && !counted[m]); });
            CellClass& cls = l.cell_class[k];
            if (cls == CellClass::traversable && !obstacle_near && slope_deg[k] > c.max_slope_deg) cls = CellClass::obstacle;
            if (cls != CellClass::traversable) {
                l.cost[k] = 1.0f;
                continue;
            }
            double cost = std::max(l.step_m[k] / c.max_step_m, l.drop_m[k] / c.max_drop_m);
            cost = std::max(cost, l.roughness_m[k] / c.max_roughness_m);
            if (std::isfinite(slope_deg[k])) cost = std::max(cost, slope_deg[k] / c.max_slope_deg);
            l.cost[k] = static_cast<float>(std::min(1.0, cost));
        }
    return l;
}

// The arcs judged one swept cell at a time: its map cell from its body-frame centre (the
// same float arithmetic as the documented mapping), each map cell counted once.
std::vector<ArcVerdict> plain_arcs(const TerrainGrid& g, const TraversabilityLayers& l, const ArcSetConfig& ac,
                                   const Footprint& fp, int& best)
{
    const CandidateArcs arcs(ac, fp, g.resolution_m);
    const float c = static_cast<float>(std::cos(g.residual_yaw_rad)), s = static_cast<float>(std::sin(g.residual_yaw_rad));
    const float inv = static_cast<float>(1.0 / g.resolution_m);
    const float ox = static_cast<float>(g.origin_x_m), oy = static_cast<float>(g.origin_y_m);
    std::vector<ArcVerdict> out;
    best = -1;
    for (int a = 0; a < arcs.count(); ++a) {
        ArcVerdict v;
        v.curvature_per_m = arcs.curvature(a);
        v.clear_distance_m = ac.length_m;
        std::set<long> seen;
        double swept = 0, unknown = 0, cost = 0;
        int known = 0;
        for (const CandidateArcs::SweptCell& f : arcs.sweep(a)) {
            const float fi = (c * f.x_m - s * f.y_m - ox) * inv, fj = (s * f.x_m + c * f.y_m - oy) * inv;
            if (!(fi >= 0.0f && fj >= 0.0f && fi < static_cast<float>(g.nx) && fj < static_cast<float>(g.ny))) {
                swept += 0.25;
                unknown += 0.25;
                continue;
            }
            const long k = static_cast<long>(std::floor(fi)) * g.ny + static_cast<long>(std::floor(fj));
            if (!seen.insert(k).second) continue;
            const CellClass cls = l.cell_class[static_cast<std::size_t>(k)];
            if (cls == CellClass::obstacle || cls == CellClass::negative_obstacle) {
                v.clear_distance_m = f.s_m;
                v.blocked = true;
                break;
            }
            swept += 1;
            if (cls == CellClass::unknown) {
                unknown += 1;
            } else {
                ++known;
                cost += l.cost[static_cast<std::size_t>(k)];
            }
        }
        v.unknown_fraction = swept > 0 ? unknown / swept : 1.0;
        v.mean_cost = known > 0 ? cost / known : 0.0;
        if (ac.unknown_policy == UnknownPolicy::cautious && v.unknown_fraction > ac.max_unknown_fraction) v.blocked = true;
        v.merit = (v.clear_distance_m / ac.length_m) * (1.0 - v.unknown_fraction * ac.unknown_weight) * (1.0 - v.mean_cost);
        if (!v.blocked && (best < 0 || v.merit > out[static_cast<std::size_t>(best)].merit)) best = a;
        out.push_back(v);
    }
    return out;
}

// Float layers equal to the bit (NaN equal to NaN).
int differing(const std::vector<float>& a, const std::vector<float>& b)
{
    REQUIRE(a.size() == b.size());
    int d = 0;
    for (std::size_t k = 0; k < a.size(); ++k)
        d += (std::isnan(a[k]) && std::isnan(b[k])) || std::memcmp(&a[k], &b[k], sizeof(float)) == 0 ? 0 : 1;
    return d;
}

void compare_update(const TerrainGrid& g, const TraverseConfig& config)
{
    Traversability t{config};
    REQUIRE(t.update(g));
    const TraversabilityLayers& fast = t.result().layers;
    const TraversabilityLayers plain = plain_layers(g, config.classifier, fast.slope_deg);
    CHECK(fast.cell_class == plain.cell_class);
    CHECK(differing(fast.cost, plain.cost) == 0);
    CHECK(differing(fast.step_m, plain.step_m) == 0);
    CHECK(differing(fast.drop_m, plain.drop_m) == 0);
    CHECK(differing(fast.roughness_m, plain.roughness_m) == 0);
    CHECK(differing(fast.span_m, plain.span_m) == 0);
    CHECK(differing(fast.ground_m, plain.ground_m) == 0);
    CHECK(differing(fast.certainty, plain.certainty) == 0);
    int best = -1;
    const std::vector<ArcVerdict> arcs = plain_arcs(g, fast, config.arcs, config.footprint, best);
    REQUIRE(arcs.size() == t.result().arcs.size());
    for (std::size_t a = 0; a < arcs.size(); ++a) {
        const ArcVerdict &f = t.result().arcs[a], &p = arcs[a];
        INFO("arc " << a);
        CHECK(f.curvature_per_m == p.curvature_per_m);
        CHECK(f.clear_distance_m == p.clear_distance_m);
        CHECK(f.unknown_fraction == p.unknown_fraction);
        CHECK(f.mean_cost == p.mean_cost);
        CHECK(f.merit == p.merit);
        CHECK(f.blocked == p.blocked);
    }
    CHECK(t.result().best_arc == best);
    const auto count = [&](CellClass c) { return std::count(plain.cell_class.begin(), plain.cell_class.end(), c); };
    CHECK(t.counters().obstacle_cells == static_cast<uint64_t>(count(CellClass::obstacle)));
    CHECK(t.counters().negative_obstacle_cells == static_cast<uint64_t>(count(CellClass::negative_obstacle)));
    CHECK(t.counters().unknown_cells == static_cast<uint64_t>(count(CellClass::unknown)));
}

}  // namespace

TEST_CASE("one update equals the plain classifier and arcs on the benchmark's map")
{
    const bool avx2 = GENERATE(true, false);
    CAPTURE(avx2);
    const Avx2Allowed allowed(avx2);
    const TerrainGrid g = demo_like_map();
    compare_update(g, TraverseConfig{});
    Traversability t{TraverseConfig{}};
    REQUIRE(t.update(g));
    CHECK(t.counters().obstacle_cells > 100);  // the map holds what the comparison is about
    CHECK(t.counters().negative_obstacle_cells > 10);
    CHECK(t.counters().arcs_blocked > 5);
    CHECK(t.counters().arcs_blocked < 25);
}

TEST_CASE("one update equals the plain classifier and arcs on random maps")
{
    const bool avx2 = GENERATE(true, false);
    CAPTURE(avx2);
    const Avx2Allowed allowed(avx2);
    std::mt19937 rng(424242);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int maps = 0;
    for (const double base : {0.0, 750.0, -3.0})
        for (const auto& [nx, ny] : {std::pair{150, 150}, std::pair{61, 37}}) {
            TerrainGrid g = random_map(rng, nx, ny, base);
            g.residual_yaw_rad = (u(rng) - 0.5) * 0.6;
            g.position_m = {0, 0, base};
            for (std::size_t k = 0; k < g.cells(); ++k)
                if (g.count[k] > 0 && u(rng) < 0.2) g.age_s[k] = static_cast<float>(70 * u(rng));
            TraverseConfig config;
            if (maps % 3 == 1) {
                config.arcs.unknown_policy = UnknownPolicy::cautious;
                config.classifier.max_slope_deg = 12;
            }
            if (maps % 3 == 2) {
                config.classifier.ground_radius_m = 0.9;
                config.classifier.slope_radius_m = 0.7;
                config.classifier.shadow_radius_m = 0.9;
                config.classifier.step_radius_m = 0.5;
                config.arcs.count = 7;
            }
            CAPTURE(base, nx, ny, maps);
            compare_update(g, config);
            ++maps;
        }
    CHECK(maps == 6);
}

TEST_CASE("one update equals the plain classifier and arcs on small, thin and cut maps")
{
    const bool avx2 = GENERATE(true, false);
    CAPTURE(avx2);
    const Avx2Allowed allowed(avx2);
    // Windows cut by every edge, rows of the ground's window that fill no whole vector of 4
    // (half-widths 2, 6 and 9), unknown holes, cells of spread shares only, aged and decayed
    // cells, heights near 0 where the floats are finest.
    std::mt19937 rng(2424);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int maps = 0;
    for (const double base : {1e-4, 0.0, 120.0})
        for (const auto& [nx, ny] : {std::pair{3, 4}, std::pair{40, 1}, std::pair{1, 40}, std::pair{9, 200}, std::pair{23, 17}}) {
            TerrainGrid g = random_map(rng, nx, ny, base);
            g.residual_yaw_rad = (u(rng) - 0.5) * 0.6;
            g.position_m = {0, 0, base};
            for (std::size_t k = 0; k < g.cells(); ++k) {
                if (g.count[k] > 0 && u(rng) < 0.3) g.age_s[k] = static_cast<float>(80 * u(rng));
                if (g.count[k] > 0 && u(rng) < 0.05) {
                    g.count[k] = 3;
                    g.max_z_m[k] = g.min_z_m[k] = g.mean_z_m[k];
                }
            }
            TraverseConfig config;
            config.classifier.ground_radius_m = std::array{0.5, 1.3, 1.9}[static_cast<std::size_t>(maps % 3)];
            config.classifier.step_radius_m = maps % 2 ? 0.2 : 0.45;
            config.classifier.shadow_radius_m = std::array{0.3, 0.6, 1.0}[static_cast<std::size_t>(maps % 3)];
            config.arcs.count = 5;
            CAPTURE(base, nx, ny, maps);
            compare_update(g, config);
            ++maps;
        }
    CHECK(maps == 15);
}
