// Traversability benchmarks: one update (classes, cost, 25 arcs) of a 150x150 map with the
// default configuration, on a map like the demo's: rough ground, boxes, a wall, a ditch,
// the dead zone and the shadows unknown. Also the classifier and the arcs alone.
#include <benchmark/benchmark.h>

#include <cmath>

#include "ugv/traverse/traversability.hpp"
#include "ugv_test/terrain_grid_builder.hpp"

using namespace ugv::traverse;
using namespace ugv::traverse::test;

namespace {

TerrainGrid demo_like_map()
{
    TerrainGrid g = empty_grid();
    fill(g, [](double x, double y) {
        double z = 750.0 + 0.05 * std::sin(0.7 * x) * std::cos(0.5 * y) + 0.02 * x;
        if (x > 8 && x < 8.6 && y > -3 && y < -2.4) z += 0.6;        // box
        if (y > 7 && y < 7.3 && x > 4 && x < 25) z += 3.0;           // wall
        if (x > 14 && x < 15 && y > -6 && y < 2) z -= 0.4;           // ditch
        if (x > 18 && x < 20 && y > 2 && y < 4) z += 0.3;            // low box
        return z;
    });
    // Unknown: the dead zone before 3 m, behind the wall, beyond 25 m, and a third of the rest.
    for (int i = 0; i < g.nx; ++i)
        for (int j = 0; j < g.ny; ++j) {
            const double x = cx(g, i), y = cy(g, j);
            if (x < 3 || y > 7.3 || x > 25 || ((i * 7 + j * 13) % 3 == 0 && x > 15)) {
                const std::size_t k = static_cast<std::size_t>(i) * g.ny + j;
                g.count[k] = 0;
                g.mean_z_m[k] = g.max_z_m[k] = g.min_z_m[k] = g.variance_z_m2[k] = NAN;
            }
        }
    g.position_m = {0, 0, 750.0};
    return g;
}

void BM_Update150x150_25Arcs(benchmark::State& state)
{
    Traversability t{TraverseConfig{}};
    TerrainGrid g = demo_like_map();
    // The first map builds the arc set (BM_BuildArcSet); the loop times the updates after it.
    t.update(g);
    for (auto _ : state) {
        g.utime_us += 500'000;
        benchmark::DoNotOptimize(t.update(g));
    }
    state.counters["obstacle_cells"] = static_cast<double>(t.counters().obstacle_cells);
    state.counters["arcs_blocked"] = static_cast<double>(t.counters().arcs_blocked);
}
BENCHMARK(BM_Update150x150_25Arcs)->Unit(benchmark::kMicrosecond);

void BM_Classify150x150(benchmark::State& state)
{
    CellClassifier c{ClassifierConfig{}};
    const TerrainGrid g = demo_like_map();
    TraversabilityLayers out;
    for (auto _ : state) c.classify(g, Odometer{}, out);
}
BENCHMARK(BM_Classify150x150)->Unit(benchmark::kMicrosecond);

void BM_Judge25Arcs(benchmark::State& state)
{
    CellClassifier c{ClassifierConfig{}};
    const TerrainGrid g = demo_like_map();
    TraversabilityLayers layers;
    c.classify(g, Odometer{}, layers);
    CandidateArcs arcs(ArcSetConfig{}, Footprint{}, g.resolution_m);
    std::vector<ArcVerdict> out;
    int best = -1;
    for (auto _ : state) {
        arcs.judge(g, layers, out, best);
        benchmark::DoNotOptimize(best);
    }
}
BENCHMARK(BM_Judge25Arcs)->Unit(benchmark::kMicrosecond);

void BM_BuildArcSet(benchmark::State& state)
{
    for (auto _ : state) {
        CandidateArcs arcs(ArcSetConfig{}, Footprint{}, 0.2);
        benchmark::DoNotOptimize(arcs.count());
    }
}
BENCHMARK(BM_BuildArcSet)->Unit(benchmark::kMillisecond);

}  // namespace
