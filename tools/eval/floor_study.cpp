#include "floor_study.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>
#include <unordered_map>

namespace ugv::terrain {

std::vector<FloorStudyCase> report_cases()
{
    // The static 3DM-G (Table 3's "with IMU"): sigma 0.047 deg. Without the IMU the map
    // still needs a de for eq. 19: the same 0.047 deg, with no error added.
    return {{"no IMU", 0.0, 0.047}, {"3DM-G static", 0.047, 0.047}, {"3DM-G", 5.0, 5.0}, {"3DM-GX1", 2.0, 2.0}};
}

namespace {

// The shortest and longest range of the points that fell in each cell of the final map.
struct RangeTally
{
    struct Point
    {
        double x, y, range;
    };
    std::vector<Point> points;  // world frame

    // Keys on the snapshot's grid: cell boundaries at its origin plus multiples of its
    // resolution (the world-aligned map is not turned: its grid is the world's, shifted).
    std::unordered_map<int64_t, std::pair<double, double>> per_cell(const MapSnapshot& m) const
    {
        std::unordered_map<int64_t, std::pair<double, double>> cells;
        for (const Point& p : points) {
            auto [it, fresh] = cells.try_emplace(key(m, p.x, p.y), p.range, p.range);
            it->second.first = std::min(it->second.first, p.range);
            it->second.second = std::max(it->second.second, p.range);
        }
        return cells;
    }
    static int64_t key(const MapSnapshot& m, double x, double y)
    {
        const double ox = m.pose.position_m.x() + m.origin_x_m, oy = m.pose.position_m.y() + m.origin_y_m;
        const auto i = static_cast<int64_t>(std::floor((x - ox) / m.resolution_m));
        const auto j = static_cast<int64_t>(std::floor((y - oy) / m.resolution_m));
        return i * 1'000'000 + j;
    }
};

struct Trial
{
    MapMetrics all, several_ranges;
};

struct Scan
{
    std::vector<float> x, y, z, range, variance, t;
    void clear()
    {
        x.clear(), y.clear(), z.clear(), range.clear(), variance.clear(), t.clear();
    }
};

Trial one_trial(const FloorStudyCase& sc, StatisticsKind statistics, const FloorStudyOptions& o, uint64_t seed)
{
    MapConfig config;
    config.mode = MapMode::world_aligned;  // the static pose jitters in yaw: no rotations
    config.statistics = statistics;
    config.spread = o.spread;
    config.reference_x_m = 0.0;
    TerrainMapper mapper(config);
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> unit(0.0, 1.0);
    const double noise = sc.noise_sigma_deg * M_PI / 180.0;
    const double model = sc.model_sigma_deg * M_PI / 180.0;
    const Eigen::Vector3d laser(0.0, 0.0, o.laser_height_m);

    Scan scan;
    RangeTally tally;
    int64_t utime = 1'000'000;
    const int lines = static_cast<int>(std::lround((o.last_line_m - o.first_line_m) / o.line_spacing_m)) + 1;
    Eigen::Vector3d vehicle(0.0, 0.0, 0.0);
    for (int k = 0; k < o.nods * lines; ++k, utime += 26'600) {
        // Nodding down and up: lines far to near, then near to far, ...
        const int line = (k / lines) % 2 == 0 ? k % lines : lines - 1 - k % lines;
        const double d = o.first_line_m + line * o.line_spacing_m;
        vehicle.x() = o.speed_mps * static_cast<double>(k) * 0.0266;
        // The IMU's error for this scan: the points are computed with the wrong orientation,
        // about the laser (the pose's position keeps the laser where it is).
        const Eigen::Quaterniond error = Eigen::AngleAxisd(noise * unit(rng), Eigen::Vector3d::UnitZ()) *
                                         Eigen::AngleAxisd(noise * unit(rng), Eigen::Vector3d::UnitY()) *
                                         Eigen::AngleAxisd(noise * unit(rng), Eigen::Vector3d::UnitX());
        Pose pose;
        pose.utime_us = utime;
        pose.orientation = error;
        pose.position_m = vehicle + laser - (error * laser);
        pose.orientation_covariance_rad2 = Eigen::Matrix3d::Identity() * model * model;
        mapper.add_pose(pose);
        // The scan plane tilted down so that the centre beam meets the floor d ahead.
        const double tilt = std::atan2(o.laser_height_m, d);
        scan.clear();
        for (double b = -90.0; b <= 90.0 + 1e-9; b += o.beam_step_deg) {
            const double br = b * M_PI / 180.0;
            const Eigen::Vector3d dir(std::cos(br) * std::cos(tilt), std::sin(br), -std::cos(br) * std::sin(tilt));
            if (dir.z() > -1e-6) continue;
            const double true_range = o.laser_height_m / -dir.z();
            if (true_range > o.max_range_m) continue;
            const double r = true_range + o.range_sigma_m * unit(rng);
            const Eigen::Vector3d p = laser + r * dir;  // body frame (= world: the truth is level)
            scan.x.push_back(static_cast<float>(p.x()));
            scan.y.push_back(static_cast<float>(p.y()));
            scan.z.push_back(static_cast<float>(p.z()));
            scan.range.push_back(static_cast<float>(r));
            scan.variance.push_back(static_cast<float>(o.range_sigma_m * o.range_sigma_m));
            scan.t.push_back(0.0f);
            tally.points.push_back({vehicle.x() + p.x(), vehicle.y() + p.y(), r});
        }
        PointBatch batch{utime, scan.x.size(), scan.x.data(), scan.y.data(), scan.z.data(), scan.range.data(),
                         scan.variance.data(), scan.t.data()};
        mapper.fuse(batch);
    }
    // Read the map with the true (level) pose.
    Pose truth_pose;
    truth_pose.utime_us = utime;
    truth_pose.position_m = vehicle;
    mapper.add_pose(truth_pose);
    MapSnapshot snapshot;
    mapper.snapshot(snapshot);
    Trial trial;
    trial.all = evaluate(snapshot, [](double, double) { return 0.0; });
    const auto ranges = tally.per_cell(snapshot);
    trial.several_ranges = evaluate(snapshot, [&](double x, double y) {
        const auto it = ranges.find(RangeTally::key(snapshot, x, y));
        const bool several = it != ranges.end() && it->second.second >= o.several_ranges_ratio * it->second.first;
        return several ? 0.0 : NAN;
    });
    return trial;
}

// Sums of trials' metrics, averaged by finish().
struct MetricsAverage
{
    MapMetrics sum;
    double bias2 = 0.0, rmse2 = 0.0;
    void add(const MapMetrics& m)
    {
        sum.cells += m.cells;
        sum.known += m.known;
        sum.bias_m += m.bias_m;
        bias2 += m.bias_m * m.bias_m;
        rmse2 += m.rmse_m * m.rmse_m;
        sum.mean_cell_variance_m2 += m.mean_cell_variance_m2;
        sum.coverage += m.coverage;
    }
    // The averages over n trials and the standard error of the mean bias.
    std::pair<MapMetrics, double> finish(int n) const
    {
        MapMetrics m = sum;
        const double dn = n;
        m.cells = static_cast<int>(sum.cells / n);
        m.known = static_cast<int>(sum.known / n);
        m.bias_m /= dn;
        m.rmse_m = std::sqrt(rmse2 / dn);
        m.mean_cell_variance_m2 /= dn;
        m.coverage /= dn;
        const double se = n > 1 ? std::sqrt(std::max(0.0, bias2 / dn - m.bias_m * m.bias_m) / (dn - 1.0)) : 0.0;
        return {m, se};
    }
};

}  // namespace

FloorStudyResult run_floor_study(const FloorStudyCase& scenario, StatisticsKind statistics,
                                 const FloorStudyOptions& options)
{
    FloorStudyResult result{scenario, statistics, {}, {}};
    MetricsAverage all, several;
    for (int k = 0; k < options.trials; ++k) {
        // The same seed for both statistics: they see the same points.
        const Trial t = one_trial(scenario, statistics, options, options.seed * 1000 + static_cast<uint64_t>(k));
        all.add(t.all);
        several.add(t.several_ranges);
    }
    std::tie(result.metrics, result.bias_standard_error_m) = all.finish(options.trials);
    result.several_ranges = several.finish(options.trials).first;
    return result;
}

}  // namespace ugv::terrain
