// Traversability benchmarks: one update (classes, cost, 25 arcs) of a 150x150 map with the
// default configuration, on a map like the demo's: rough ground, boxes, a wall, a ditch,
// the dead zone and the shadows unknown. Also the classifier and the arcs alone.
#include <benchmark/benchmark.h>

#include <cmath>

#include "ugv/traverse/traversability.hpp"
#include "traverse_maps.hpp"

using namespace ugv::traverse;
using namespace ugv::traverse::test;

namespace {

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
