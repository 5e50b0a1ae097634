// Terrain map benchmarks: fusion throughput (points/s as items_per_second), one rotation
// and one wrap of a 150x150 map, and the resident memory of a 150x150 mapper. The fusion's
// placement and the rotation run the best code the CPU has (simd.hpp); the _Generic
// variants run the baseline code.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "ugv/terrain/egocentric_grid.hpp"
#include "ugv/terrain/simd.hpp"
#include "ugv/terrain/terrain_mapper.hpp"

using namespace ugv::terrain;

namespace {

// One 361-beam scan (180 deg at 0.5 deg) of a nodding laser 0.87 m up, tilted down by
// tilt_rad, hitting flat ground: points in the body frame with a 1 cm sensor sigma.
struct Scan
{
    std::vector<float> x, y, z, range, variance, t;
    explicit Scan(double tilt_rad)
    {
        const double height = 0.87;
        for (int k = 0; k < 361; ++k) {
            const double bearing = (-90.0 + 0.5 * k) * M_PI / 180.0;
            // The beam direction in the body frame: bearing about Z, then tilted down.
            const double dx = std::cos(bearing) * std::cos(tilt_rad);
            const double dy = std::sin(bearing) * std::cos(tilt_rad);
            const double dz = -std::sin(tilt_rad);
            const double r = std::min(height / -dz, 40.0);
            x.push_back(static_cast<float>(0.5 + r * dx));
            y.push_back(static_cast<float>(r * dy));
            z.push_back(static_cast<float>(height + r * dz));
            range.push_back(static_cast<float>(r));
            variance.push_back(1e-4f);
            t.push_back(static_cast<float>(k * 13.3e-3 / 360.0));
        }
    }
    PointBatch batch(int64_t utime_us) const
    {
        return {utime_us, x.size(), x.data(), y.data(), z.data(), range.data(), variance.data(), t.data()};
    }
};

Pose pose_at(int64_t t_us, double x, double yaw, double orientation_sigma_deg)
{
    Pose p;
    p.utime_us = t_us;
    p.position_m = {x, 0.0, 0.0};
    p.orientation = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ());
    const double s = orientation_sigma_deg * M_PI / 180.0;
    p.orientation_covariance_rad2 = Eigen::Matrix3d::Identity() * s * s;
    return p;
}

// Fuses the 16 scans in turn. scan_span_s: the time one scan spans (13.3 ms as the LMS's
// 180 deg; above max_interpolation_span_s it is fused in runs). flush_every: the pending
// spread shares go into the cells every this many scans, as the map's moves do while driving
// (a wrap every 2.7 scans at 3 m/s); 0: never (plain fusion has none).
void run_fusion(benchmark::State& state, MapConfig config, double orientation_sigma_deg, double scan_span_s = 13.3e-3,
                int flush_every = 0)
{
    TerrainMapper mapper(config);
    mapper.add_pose(pose_at(0, 0.0, 0.0, orientation_sigma_deg));
    mapper.add_pose(pose_at(300'000, 0.1, 0.01, orientation_sigma_deg));
    // 16 scans at tilts from 3 to 18 deg cover the ground 2.8 to 16 m ahead.
    std::vector<Scan> scans;
    for (int k = 0; k < 16; ++k) {
        scans.emplace_back((3.0 + k) * M_PI / 180.0);
        for (float& t : scans.back().t) t *= static_cast<float>(scan_span_s / 13.3e-3);
    }
    std::size_t k = 0;
    int since_flush = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(mapper.fuse(scans[k].batch(50'000)));
        k = (k + 1) & 15;
        if (flush_every > 0 && ++since_flush == flush_every) {
            mapper.flush_spread();
            since_flush = 0;
        }
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * 361);
    state.counters["spread_fraction"] =
        static_cast<double>(mapper.counters().points_spread) / static_cast<double>(mapper.counters().points_fused);
}

void BM_Fusion_VarianceWeighted(benchmark::State& state)
{
    state.counters["avx2"] = simd_level() == SimdLevel::avx2;
    run_fusion(state, MapConfig{}, 0.2);
}
BENCHMARK(BM_Fusion_VarianceWeighted);

// The same with the generic 4-wide placement, which a CPU without AVX2 and FMA runs.
void BM_Fusion_VarianceWeighted_Generic(benchmark::State& state)
{
    const ScopedSimdLevel use(SimdLevel::generic);
    run_fusion(state, MapConfig{}, 0.2);
}
BENCHMARK(BM_Fusion_VarianceWeighted_Generic);

void BM_Fusion_Classical(benchmark::State& state)
{
    MapConfig c;
    c.statistics = StatisticsKind::classical;
    run_fusion(state, c, 0.2);
}
BENCHMARK(BM_Fusion_Classical);

void BM_Fusion_WorldAligned(benchmark::State& state)
{
    MapConfig c;
    c.mode = MapMode::world_aligned;
    run_fusion(state, c, 0.2);
}
BENCHMARK(BM_Fusion_WorldAligned);

// The configuration the daemon runs: its defaults (section 3.5 spreading, summed-area form)
// with the 3DM-GX1's 2 deg: 62 % of the points spread over up to 5x5 cells; the pending
// shares flushed every 3 scans (the wraps of a 3 m/s drive), or every 16 (standing, or slow).
void BM_Fusion_Default_GX1_2deg(benchmark::State& state) { run_fusion(state, MapConfig{}, 2.0, 13.3e-3, 3); }
BENCHMARK(BM_Fusion_Default_GX1_2deg);
void BM_Fusion_Default_GX1_2deg_Flush16(benchmark::State& state) { run_fusion(state, MapConfig{}, 2.0, 13.3e-3, 16); }
BENCHMARK(BM_Fusion_Default_GX1_2deg_Flush16);

// The same with the cell-by-cell reference spreading (spread_exact).
void BM_Fusion_Default_GX1_2deg_Exact(benchmark::State& state)
{
    MapConfig c;
    c.spread_form = SpreadForm::exact;
    run_fusion(state, c, 2.0);
}
BENCHMARK(BM_Fusion_Default_GX1_2deg_Exact);

// The same with each summed-area form named (the default is one of them).
void run_spread_form(benchmark::State& state, SpreadForm form)
{
    MapConfig c;
    c.spread_form = form;
    run_fusion(state, c, 2.0, 13.3e-3, 3);
}
void BM_Fusion_Default_GX1_2deg_SummedArea(benchmark::State& state)
{
    run_spread_form(state, SpreadForm::summed_area);
}
BENCHMARK(BM_Fusion_Default_GX1_2deg_SummedArea);
void BM_Fusion_Default_GX1_2deg_Centred(benchmark::State& state) { run_spread_form(state, SpreadForm::centred); }
BENCHMARK(BM_Fusion_Default_GX1_2deg_Centred);

// 6 deg: every point spreads (the other end of the mix of the 2 deg case).
void BM_Fusion_Default_AllSpread6deg(benchmark::State& state) { run_fusion(state, MapConfig{}, 6.0, 13.3e-3, 3); }
BENCHMARK(BM_Fusion_Default_AllSpread6deg);

// Plain fusion with scans spanning 0.09 s (one run) and 0.12 s (beyond
// max_interpolation_span_s: two runs).
void BM_Fusion_Span90ms(benchmark::State& state) { run_fusion(state, MapConfig{}, 0.2, 0.09); }
BENCHMARK(BM_Fusion_Span90ms);
void BM_Fusion_Span120ms(benchmark::State& state) { run_fusion(state, MapConfig{}, 0.2, 0.12); }
BENCHMARK(BM_Fusion_Span120ms);

// A lidar-like cloud through the same fusion, default configuration, GX1's 2 deg: 64 beams x
// 1024 azimuths (65 536 points) whose ranges on flat ground run from 10 to 100 m, over 33 ms
// (2 M points/s); the points beyond the map's 30 m are counted outside.
void BM_Fusion_Default_Lidar64x1024(benchmark::State& state)
{
    std::vector<float> x, y, z, range, variance, t;
    const int beams = 64, azimuths = 1024;
    for (int a = 0; a < azimuths; ++a) {
        const double bearing = 2.0 * M_PI * a / azimuths;
        for (int b = 0; b < beams; ++b) {
            const double r = 10.0 * std::pow(10.0, static_cast<double>(b) / (beams - 1));  // 10 .. 100 m
            const double ground = std::sqrt(std::max(r * r - 1.8 * 1.8, 0.0));
            x.push_back(static_cast<float>(ground * std::cos(bearing)));
            y.push_back(static_cast<float>(ground * std::sin(bearing)));
            z.push_back(0.0f);
            range.push_back(static_cast<float>(r));
            variance.push_back(4e-4f);
            t.push_back(static_cast<float>(0.033 * a / azimuths));
        }
    }
    TerrainMapper mapper{MapConfig{}};
    mapper.add_pose(pose_at(0, 0.0, 0.0, 2.0));
    mapper.add_pose(pose_at(300'000, 0.1, 0.01, 2.0));
    const PointBatch cloud{50'000, x.size(), x.data(), y.data(), z.data(), range.data(), variance.data(), t.data()};
    for (auto _ : state) {
        benchmark::DoNotOptimize(mapper.fuse(cloud));
        mapper.flush_spread();
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(x.size()));
    state.counters["in_map_fraction"] =
        static_cast<double>(mapper.counters().points_fused) /
        static_cast<double>(mapper.counters().points_fused + mapper.counters().rejected_outside_map);
    state.counters["spread_fraction"] =
        static_cast<double>(mapper.counters().points_spread) / static_cast<double>(mapper.counters().points_fused);
}
BENCHMARK(BM_Fusion_Default_Lidar64x1024)->Unit(benchmark::kMicrosecond);

// Every cell known (known_radius_m = 0), or only those within known_radius_m ahead of the
// rear edge's centre: a half disc of 14.5 m holds 37 % of the 30 m x 30 m map, the share of
// known cells in the demo's maps.
EgocentricGrid full_grid(double known_radius_m = 0.0)
{
    EgocentricGrid g(150, 150, 0.2);
    for (int i = 0; i < 150; ++i) {
        for (int j = 0; j < 150; ++j) {
            const double x = (i + 0.5) * 0.2, y = -15.0 + (j + 0.5) * 0.2;
            if (known_radius_m > 0.0 && std::hypot(x, y) > known_radius_m) continue;
            float xr = 0, yr = 0;
            const int cell = g.locate(static_cast<float>((i + 0.3) * 0.2), static_cast<float>(-15.0 + (j + 0.6) * 0.2), xr, yr);
            g.fuse(cell, xr, yr, 0.01 * i, 100.0f, 0);
            g.fuse(cell, xr * 0.5f, yr, 0.01 * j, 50.0f, 0);
        }
    }
    return g;
}

// One rotation by theta_d (5 deg) of `map` (eq. 9-16), from a fresh copy each time.
void rotate_each_iteration(benchmark::State& state, const EgocentricGrid& map)
{
    EgocentricGrid g = map;
    for (auto _ : state) {
        state.PauseTiming();
        g = map;
        state.ResumeTiming();
        benchmark::DoNotOptimize(g.transform(5.0 * M_PI / 180.0, 0.1, 0.0));
    }
}

// A full 150x150 map, with the best code this CPU runs (simd.hpp; the counter says which).
void BM_Rotation150(benchmark::State& state)
{
    state.counters["avx2"] = simd_level() == SimdLevel::avx2;
    rotate_each_iteration(state, full_grid());
}
BENCHMARK(BM_Rotation150)->Unit(benchmark::kMicrosecond);

// A map as known as the demo's (37 % of the cells; the rest unknown).
void BM_Rotation150_DemoCoverage(benchmark::State& state) { rotate_each_iteration(state, full_grid(14.5)); }
BENCHMARK(BM_Rotation150_DemoCoverage)->Unit(benchmark::kMicrosecond);

// The same two with the generic 4-wide code, which a CPU without AVX2 and FMA runs.
void rotate_generic(benchmark::State& state, const EgocentricGrid& map)
{
    const ScopedSimdLevel use(SimdLevel::generic);
    rotate_each_iteration(state, map);
}
void BM_Rotation150_Generic(benchmark::State& state) { rotate_generic(state, full_grid()); }
BENCHMARK(BM_Rotation150_Generic)->Unit(benchmark::kMicrosecond);
void BM_Rotation150_DemoCoverage_Generic(benchmark::State& state) { rotate_generic(state, full_grid(14.5)); }
BENCHMARK(BM_Rotation150_DemoCoverage_Generic)->Unit(benchmark::kMicrosecond);

// One rotation by theta_d of a live full map turned in place, +5 and -5 deg in turn (no fresh
// copy: the pool's order is what earlier rotations and merges left). The map is refilled
// every 64 rotations (outside the timing), as cells turn out at its corners.
void BM_Rotation150_InPlace(benchmark::State& state)
{
    const EgocentricGrid full = full_grid();
    EgocentricGrid g = full;
    int k = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(g.transform((k & 1 ? -5.0 : 5.0) * M_PI / 180.0, 0.1, 0.0));
        if (++k == 64) {
            state.PauseTiming();
            g = full;
            k = 0;
            state.ResumeTiming();
        }
    }
}
BENCHMARK(BM_Rotation150_InPlace)->Unit(benchmark::kMicrosecond);

// Wraps of full rows (eq. 5-8): each call clears one row of 150 known cells and moves the
// index; the map is refilled every 150 rows (outside the timing). Items: rows.
void BM_Wrap150_FullRows(benchmark::State& state)
{
    const EgocentricGrid full = full_grid();
    EgocentricGrid g = full;
    int k = 0;
    for (auto _ : state) {
        g.wrap_forward(1);
        benchmark::ClobberMemory();
        if (++k == 150) {
            state.PauseTiming();
            g = full;
            k = 0;
            state.ResumeTiming();
        }
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations()));
}
BENCHMARK(BM_Wrap150_FullRows);

// A sideways move of one column (the re-centring of a sideways drift), each one clearing a
// column of 150 known cells: one way, on a full map refilled every 64 moves (outside the
// timing), the direction changing at each refill: by the column ring (what
// the mapper runs), and by the full transform it replaced (the same map, for the ratio).
template <bool kByTransform>
void column_moves(benchmark::State& state)
{
    const EgocentricGrid full = full_grid();
    EgocentricGrid g = full;
    int k = 0, columns = 1;
    for (auto _ : state) {
        if constexpr (kByTransform)
            benchmark::DoNotOptimize(g.transform(0.0, 0.0, columns * 0.2));
        else
            benchmark::DoNotOptimize(g.shift_columns(columns));
        if (++k == 64) {
            state.PauseTiming();
            g = full;
            k = 0;
            columns = -columns;
            state.ResumeTiming();
        }
    }
}
void BM_ColumnMove150(benchmark::State& state) { column_moves<false>(state); }
BENCHMARK(BM_ColumnMove150)->Unit(benchmark::kMicrosecond);
void BM_ColumnMove150_Transform(benchmark::State& state) { column_moves<true>(state); }
BENCHMARK(BM_ColumnMove150_Transform)->Unit(benchmark::kMicrosecond);

// A pose update that wraps one row: the whole checkScrollMap path of the mapper.
void BM_PoseUpdateWrap150(benchmark::State& state)
{
    TerrainMapper mapper(MapConfig{});
    int64_t t = 0;
    double x = 0.0;
    for (auto _ : state) {
        t += 100'000;
        x += 0.2;
        mapper.add_pose(pose_at(t, x, 0.0, 0.2));
    }
    state.counters["wraps_per_update"] =
        static_cast<double>(mapper.counters().wraps) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_PoseUpdateWrap150);

long resident_kb()
{
    std::ifstream status("/proc/self/status");
    std::string line;
    while (std::getline(status, line))
        if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
    return -1;
}

// Resident memory of a 150x150 egocentric mapper, filled and rotated once (both index
// grids touched), and of the snapshot it publishes. Reported as counters, in MB.
void BM_ResidentMemory150(benchmark::State& state)
{
    for (auto _ : state) {
        const long before_kb = resident_kb();
        TerrainMapper mapper(MapConfig{});
        mapper.add_pose(pose_at(0, 0.0, 0.0, 0.2));
        Scan scan(10.0 * M_PI / 180.0);
        for (int k = 0; k < 100; ++k) mapper.fuse(scan.batch(0));
        mapper.add_pose(pose_at(100'000, 0.0, 0.1, 0.2));  // one rotation: the working index grid is touched
        MapSnapshot snapshot;
        mapper.snapshot(snapshot);
        const long after_kb = resident_kb();
        state.counters["mapper_MB"] = static_cast<double>(after_kb - before_kb) / 1024.0;
        state.counters["process_rss_MB"] = static_cast<double>(after_kb) / 1024.0;
        benchmark::DoNotOptimize(snapshot.mean_z_m.data());
    }
}
BENCHMARK(BM_ResidentMemory150)->Iterations(1);

}  // namespace
