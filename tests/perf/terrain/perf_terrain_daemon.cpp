// The terrain daemon's publication and replay paths: serialising one 150x150 map (snapshot
// of the mapper, conversion to terrain_map_t, LCM encode) and `ugv-terrain --replay` of a
// 10-minute two-laser log (process start to exit, including writing the maps' log).
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <ugv/terrain_map_t.hpp>
#include <ugv_test/process.hpp>

#include "terrain_messages.hpp"
#include "synthetic_log.hpp"
#include "ugv/terrain/terrain_mapper.hpp"

using namespace ugv;

namespace {

// A mapper whose every cell holds a few samples, and the pose message it refers to.
struct FullMap
{
    terrain::TerrainMapper mapper{terrain::MapConfig{}};
    pose_t pose{};

    FullMap()
    {
        pose.utime = 1'000'000;
        pose.orientation[0] = 1.0;
        pose.status = pose_t::STATUS_OK;
        mapper.add_pose(terrain_daemon::to_pose(pose));
        // One point per cell centre of the 30 m x 30 m map ahead of the rear bumper.
        std::vector<float> x, y, z, range, variance, t;
        for (int i = 0; i < 150; ++i) {
            for (int j = 0; j < 150; ++j) {
                x.push_back(static_cast<float>(-0.5 + (i + 0.5) * 0.2));
                y.push_back(static_cast<float>(-15.0 + (j + 0.5) * 0.2));
                z.push_back(static_cast<float>(0.01 * (i % 7)));
                range.push_back(std::hypot(x.back(), y.back()));
                variance.push_back(1e-4f);
                t.push_back(0.0f);
            }
        }
        terrain::PointBatch batch{pose.utime, x.size(), x.data(), y.data(), z.data(), range.data(), variance.data(), t.data()};
        for (int k = 0; k < 3; ++k) mapper.fuse(batch);
    }
};

// The TERRAIN_MAP the daemon publishes, from the mapper as it stands: what maybe_publish does.
void BM_SerialiseMap150(benchmark::State& state)
{
    const FullMap full;
    terrain::MapSnapshot snapshot;
    terrain_map_t message;
    std::vector<uint8_t> buffer;
    int64_t seq = 0;
    for (auto _ : state) {
        full.mapper.snapshot(snapshot);
        terrain_daemon::to_message(snapshot, full.pose, seq++, message);
        buffer.resize(static_cast<std::size_t>(message.getEncodedSize()));
        benchmark::DoNotOptimize(message.encode(buffer.data(), 0, static_cast<int>(buffer.size())));
    }
    state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) * static_cast<int64_t>(buffer.size()));
    int known = 0;
    for (float z : snapshot.mean_z_m) known += std::isnan(z) ? 0 : 1;
    state.counters["known_cells"] = known;
    state.counters["message_kB"] = static_cast<double>(buffer.size()) / 1024.0;
}
BENCHMARK(BM_SerialiseMap150)->Unit(benchmark::kMicrosecond);

// Two nodding lasers for 10 minutes at their real rate (37.5 Hz x 361 points each) and POSE
// at 10 Hz, generated once per run into a temporary folder.
struct TwoLaserLog
{
    test::TempDir dir;
    std::string log = dir / "drive.log";
    std::string config = dir / "terrain.toml";
    std::size_t clouds = 0, points = 0;

    TwoLaserLog()
    {
        test::SyntheticDrive drive;
        drive.duration_s = 600.0;
        drive.turn_rate_rad_s = 0.1;  // a 10 m circle at 1 m/s: a rotation every 0.9 s
        drive.lasers = {"left", "right"};
        drive.cloud_period_us = 26'667;  // 37.5 Hz per laser
        drive.points_per_cloud = 361;
        drive.write_log(log);
        const int64_t step_us = drive.cloud_period_us / 2, first_us = 20'000;  // as SyntheticDrive::events
        clouds = static_cast<std::size_t>((static_cast<int64_t>(drive.duration_s * 1e6) - first_us) / step_us + 1);
        points = clouds * static_cast<std::size_t>(drive.points_per_cloud);
        test::write_file(config, "publish_hz = 2.0\n");
    }
};

double children_cpu_s()
{
    rusage u{};
    getrusage(RUSAGE_CHILDREN, &u);
    return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
           1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// Wall time of the process (the figure of the goal; on a loaded machine it includes waiting
// for a core), and its CPU time and peak resident memory as counters.
void BM_Replay10MinTwoLasers(benchmark::State& state)
{
    static const TwoLaserLog input;
    const std::string out = input.dir / "maps.log";
    int rc = 0;
    const double cpu_before_s = children_cpu_s();
    for (auto _ : state) {
        const auto start = std::chrono::steady_clock::now();
        rc = test::run({test::bin("ugv-terrain"), "--config", input.config, "--replay", input.log, "--out", out},
                       input.dir / "stdout.txt", input.dir / "stderr.txt", 600.0);
        state.SetIterationTime(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    if (rc != 0) state.SkipWithError(("ugv-terrain exited with " + std::to_string(rc)).c_str());
    rusage u{};
    getrusage(RUSAGE_CHILDREN, &u);
    state.counters["daemon_cpu_s"] = (children_cpu_s() - cpu_before_s) / static_cast<double>(state.iterations());
    state.counters["daemon_peak_rss_MB"] = static_cast<double>(u.ru_maxrss) / 1024.0;
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * input.points));
    state.counters["log_MB"] = static_cast<double>(std::filesystem::file_size(input.log)) / 1e6;
    state.counters["maps_MB"] = static_cast<double>(std::filesystem::file_size(out)) / 1e6;
}
BENCHMARK(BM_Replay10MinTwoLasers)->UseManualTime()->Iterations(3)->Unit(benchmark::kMillisecond);

}  // namespace
