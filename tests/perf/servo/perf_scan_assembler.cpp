// Throughput of the nodding-laser assembler: points per second for LMS-sized scans
// (361 beams, 180 deg at 0.5 deg, 13.3 ms of beams) with the servo sampled at 100 Hz.
#include <benchmark/benchmark.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "ugv/nodscan/scan_assembler.hpp"

using namespace ugv::nodscan;

static void BM_AssembleScan(benchmark::State& state)
{
    const auto beams = static_cast<std::size_t>(state.range(0));
    AssemblerConfig cfg;
    cfg.mount.axis_xyz_m = {0.3, 0.0, 0.87};
    cfg.mount.axis_rpy_rad = {0.0, 0.01, 0.0};
    cfg.mount.laser_xyz_m = {0.05, 0.0, 0.04};
    ScanAssembler assembler(cfg);
    ServoHistory servo;
    for (int k = 0; k <= 200; ++k) servo.add({k * 10'000, 0.3 + 0.2 * std::sin(k * 0.05)});
    std::vector<float> ranges(beams);
    for (std::size_t i = 0; i < beams; ++i) ranges[i] = (i % 50 == 7) ? NAN : 2.0f + 0.01f * static_cast<float>(i % 300);
    ScanView scan;
    scan.utime = 500'000;
    scan.angle_min = -std::numbers::pi / 2;
    scan.angle_increment = std::numbers::pi / static_cast<double>(beams - 1);
    scan.time_increment = 0.0133 / static_cast<double>(beams);
    scan.range_max = 80.0;
    scan.ranges = ranges.data();
    scan.n = beams;
    PointCloud cloud;
    std::size_t points = 0;
    for (auto _ : state) {
        const auto st = assembler.assemble(scan, servo, cloud);
        points += st.points + st.dropped_invalid;
        benchmark::DoNotOptimize(cloud.z.data());
    }
    state.counters["points/s"] = benchmark::Counter(static_cast<double>(points), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_AssembleScan)->Arg(361)->Arg(10'000);
