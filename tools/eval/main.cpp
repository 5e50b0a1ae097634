// ugv-eval: terrain maps against ground truth.
//   ugv-eval compare LOG [--truth FILE | --flat Z [--box X0,Y0,X1,Y1,H ...]] [--all]
//       the maps of a log (the last, or all) against a height field (ugv-sim world's
//       truth.hf, or a flat floor with boxes): RMSE, bias, coverage, obstacle detection,
//       and the cells' highest samples against the truth (how tall an obstacle's cell says it is).
//   ugv-eval traverse LOG --truth RUN/truth.hf [--all|--last]
//       the traversability maps and candidate arcs of a log against the truth
//       (traverse_score.hpp, docs/traverse.md section 4).
//   ugv-eval diff A.lcm B.lcm [--pair time|last] [--max-dz M] [--max-one-sided F] [--all]
//       the maps of two logs against each other (map_diff.hpp).
//   ugv-eval interlace LOG [--json]
//       which sweep order of an interlacing laser fits a nodding log (interlace_command.hpp).
//   ugv-eval coverage LOG [--ahead X0,X1] [--half-width W] [--turn DEG] [--window S] [--all]
//       the known share of the area ahead of the vehicle in each map, summarised over the
//       window after a turn (docs/simulator.md, "Two lasers").
//   ugv-eval attitude LOG [--pose-log LOG2] [--turn-rate DPS] [--standing-speed MPS]
//       roll/pitch/yaw error of the IMU's own output and of the pose against SIM_TRUTH,
//       standing, straight and turning (attitude_command.hpp), one JSON line each.
//   ugv-eval floor-study [--trials N] [--seed S] [--spread]
//       the report's Tables 3 and 4 on a simulated flat floor, next to the report's numbers.
#include <lcm/lcm-cpp.hpp>

#include "ugv/bus/typed.hpp"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <ugv/terrain_map_t.hpp>

#include "attitude_command.hpp"
#include "floor_study.hpp"
#include "ugv/geometry/rotation.hpp"
#include "ugv/simworld/height_field.hpp"
#include "interlace_command.hpp"
#include "map_diff.hpp"
#include "truth_terrain.hpp"
#include "traverse_score.hpp"

using namespace ugv;
using namespace ugv::terrain;

namespace {

MapSnapshot to_snapshot(const terrain_map_t& m)
{
    MapSnapshot s;
    s.pose.utime_us = m.pose.utime;
    s.pose.position_m = {m.pose.position[0], m.pose.position[1], m.pose.position[2]};
    s.pose.orientation =
        Eigen::Quaterniond(m.pose.orientation[0], m.pose.orientation[1], m.pose.orientation[2], m.pose.orientation[3]);
    s.resolution_m = m.resolution;
    s.nx = m.nx;
    s.ny = m.ny;
    s.origin_x_m = m.origin_x;
    s.origin_y_m = m.origin_y;
    s.residual_yaw_rad = m.residual_yaw;
    s.mean_z_m = m.mean_z;
    s.variance_z_m2 = m.variance_z;
    s.count = m.count;
    s.max_z_m = m.max_z;
    s.min_z_m = m.min_z;
    s.age_s = m.age_s;
    return s;
}

struct Box
{
    double x0, y0, x1, y1, h;
};

using HeightFn = std::function<double(double x_m, double y_m)>;

int compare(const std::string& path, const std::string& channel, const HeightFn& truth, const HeightFn& ground,
            double obstacle_height, bool all)
{
    lcm::LogFile log(path, "r");
    if (!log.good()) {
        std::fprintf(stderr, "ugv-eval: %s: not an LCM log\n", path.c_str());
        return 2;
    }
    terrain_map_t m;
    std::vector<uint8_t> last;
    int maps = 0;
    int malformed = 0;
    auto report = [&](const terrain_map_t& map) {
        const MapMetrics r = evaluate(to_snapshot(map), truth, obstacle_height, ground);
        std::printf("{\"utime\": %lld, \"known\": %d, \"coverage\": %.4f, \"bias_m\": %.5f, \"rmse_m\": %.5f, "
                    "\"mean_cell_variance_m2\": %.6f, \"obstacle_cells\": %d, \"obstacles_detected\": %d, "
                    "\"false_obstacles\": %d, \"max_bias_m\": %.5f, \"max_rmse_m\": %.5f, "
                    "\"obstacle_mean_error_m\": %.5f, \"obstacle_max_error_m\": %.5f}\n",
                    static_cast<long long>(map.utime), r.known, r.coverage, r.bias_m, r.rmse_m,
                    r.mean_cell_variance_m2, r.obstacle_cells, r.obstacles_detected, r.false_obstacles, r.max_bias_m,
                    r.max_rmse_m, r.obstacle_mean_error_m, r.obstacle_max_error_m);
    };
    while (const lcm::LogEvent* ev = log.readNextEvent()) {
        if (ev->channel != channel) continue;
        if (!ugv::bus::decode_checked(ev->data, static_cast<std::size_t>(ev->datalen), m)) {
            ++malformed;
            continue;
        }
        ++maps;
        if (all) report(m);
        const auto* p = static_cast<const uint8_t*>(ev->data);
        last.assign(p, p + ev->datalen);
    }
    if (malformed > 0)
        std::fprintf(stderr, "ugv-eval: %d message(s) on %s in %s are not terrain maps (skipped)\n", malformed,
                     channel.c_str(), path.c_str());
    if (maps == 0) {
        std::fprintf(stderr, "ugv-eval: no map on %s in %s\n", channel.c_str(), path.c_str());
        return 1;
    }
    if (!all) {
        m.decode(last.data(), 0, static_cast<int>(last.size()));
        report(m);
    }
    return 0;
}

struct CoverageOptions
{
    std::string channel = "TERRAIN_MAP";
    BodyArea area;
    double turn_deg = 80.0;
    double window_s = 5.0;
    bool all = false;
};

// The known share of the area ahead in each map; summarised over the window that starts
// with the first map turned turn_deg from the first map's heading (after a turn the map
// faces ground it has not seen: the report's figure 19). Exit 1: no map, or no such turn.
int coverage(const std::string& path, const CoverageOptions& o)
{
    lcm::LogFile log(path, "r");
    if (!log.good()) {
        std::fprintf(stderr, "ugv-eval: %s: not an LCM log\n", path.c_str());
        return 2;
    }
    struct Row
    {
        int64_t utime;
        double turned_deg;
        AreaCoverage c;
    };
    std::vector<Row> rows;
    terrain_map_t m;
    double first_yaw = 0.0;
    int malformed = 0;
    while (const lcm::LogEvent* ev = log.readNextEvent()) {
        if (ev->channel != o.channel) continue;
        if (!ugv::bus::decode_checked(ev->data, static_cast<std::size_t>(ev->datalen), m)) {
            ++malformed;
            continue;
        }
        const MapSnapshot snap = to_snapshot(m);
        const double yaw = snap.pose.yaw_rad();
        if (rows.empty()) first_yaw = yaw;
        const double turned = ugv::geometry::wrap_angle(yaw - first_yaw) * 180.0 / M_PI;
        rows.push_back({m.utime, turned, area_coverage(snap, o.area)});
        if (o.all)
            std::printf("{\"utime\": %lld, \"turned_deg\": %.1f, \"cells\": %d, \"known\": %d, \"coverage\": %.4f}\n",
                        static_cast<long long>(m.utime), turned, rows.back().c.cells, rows.back().c.known,
                        rows.back().c.coverage);
    }
    if (malformed > 0)
        std::fprintf(stderr, "ugv-eval: %d message(s) on %s in %s are not terrain maps (skipped)\n", malformed,
                     o.channel.c_str(), path.c_str());
    if (rows.empty()) {
        std::fprintf(stderr, "ugv-eval: no map on %s in %s\n", o.channel.c_str(), path.c_str());
        return 1;
    }
    const auto turn = std::find_if(rows.begin(), rows.end(), [&](const Row& r) { return std::abs(r.turned_deg) >= o.turn_deg; });
    if (turn == rows.end()) {
        std::fprintf(stderr, "ugv-eval: %s: no map turned %.0f deg from the first one's heading\n", path.c_str(), o.turn_deg);
        return 1;
    }
    const int64_t end = turn->utime + static_cast<int64_t>(o.window_s * 1e6);
    int n = 0;
    double sum_cov = 0.0, sum_known = 0.0, min_cov = 1.0, max_cov = 0.0;
    for (auto r = turn; r != rows.end() && r->utime < end; ++r) {
        ++n;
        sum_cov += r->c.coverage;
        sum_known += r->c.known;
        min_cov = std::min(min_cov, r->c.coverage);
        max_cov = std::max(max_cov, r->c.coverage);
    }
    std::printf("{\"maps\": %d, \"turn_utime\": %lld, \"window_s\": %.1f, \"area_cells\": %d, \"mean_known\": %.1f, "
                "\"mean_coverage\": %.4f, \"min_coverage\": %.4f, \"max_coverage\": %.4f}\n",
                n, static_cast<long long>(turn->utime), o.window_s, turn->c.cells, sum_known / n, sum_cov / n, min_cov,
                max_cov);
    return 0;
}

void study_table(const FloorStudyOptions& o, bool with_report)
{
    // The report's Tables 3 and 4 (z in m; its sigma^2 column is labelled "mm").
    struct Reported
    {
        const char* name;
        double classical_z, classical_var, weighted_z, weighted_var;
    };
    const Reported reported[] = {{"no IMU", 0.0060, 0.035, 0.0055, 0.029},
                                 {"3DM-G static", 0.0015, 0.038, 0.0015, 0.031},
                                 {"3DM-G", -0.211, 25.7, -0.182, 18.7},
                                 {"3DM-GX1", -0.077, 3.9, -0.068, 2.9}};
    std::printf("\nFlat floor, laser at %.2f m, lines every %.2f m from %.1f to %.1f m, %d nod(s), %.1f m/s, "
                "%d trial(s), seed %llu%s\n",
                o.laser_height_m, o.line_spacing_m, o.first_line_m, o.last_line_m, o.nods, o.speed_mps, o.trials,
                static_cast<unsigned long long>(o.seed), o.spread ? ", spreading on" : "");
    std::printf("%-13s %-12s | %10s %9s %10s %12s %8s | %9s %9s\n", "IMU", "statistics", "mean z (m)", "+/- se",
                "rmse z (m)", "cell var(m2)", "coverage", "report z", "report s2");
    for (const FloorStudyCase& c : report_cases()) {
        const Reported* rep = nullptr;
        for (const Reported& r : reported)
            if (with_report && c.name == r.name) rep = &r;
        FloorStudyResult cl = run_floor_study(c, StatisticsKind::classical, o);
        FloorStudyResult vw = run_floor_study(c, StatisticsKind::variance_weighted, o);
        for (const FloorStudyResult* r : {&cl, &vw}) {
            const bool classical = r->statistics == StatisticsKind::classical;
            std::printf("%-13s %-12s | %10.5f %9.5f %10.5f %12.6f %8.3f | %9.4f %9.3f\n", c.name.c_str(),
                        classical ? "classical" : "variance-wt", r->metrics.bias_m, r->bias_standard_error_m,
                        r->metrics.rmse_m, r->metrics.mean_cell_variance_m2, r->metrics.coverage,
                        rep ? (classical ? rep->classical_z : rep->weighted_z) : NAN,
                        rep ? (classical ? rep->classical_var : rep->weighted_var) : NAN);
        }
        const double rmse_gain = 1.0 - vw.metrics.rmse_m / std::max(1e-12, cl.metrics.rmse_m);
        const double var_gain =
            1.0 - vw.metrics.mean_cell_variance_m2 / std::max(1e-15, cl.metrics.mean_cell_variance_m2);
        std::printf("%-13s variance-weighted vs classical: rmse %+.1f%%, cell variance %+.0f%%", c.name.c_str(),
                    -100.0 * rmse_gain, -100.0 * var_gain);
        const MapMetrics &cs = cl.several_ranges, &vs = vw.several_ranges;
        if (cs.known > 0)
            std::printf("; over the %d cells seen from ranges %.0fx apart: rmse %.5f / %.5f (%+.1f%%)", cs.known,
                        o.several_ranges_ratio, cs.rmse_m, vs.rmse_m,
                        -100.0 * (1.0 - vs.rmse_m / std::max(1e-12, cs.rmse_m)));
        if (rep)
            std::printf(" (report: |mean z| %+.0f%%, s2 %+.0f%%)",
                        -100.0 * (1.0 - std::abs(rep->weighted_z) / std::abs(rep->classical_z)),
                        -100.0 * (1.0 - rep->weighted_var / rep->classical_var));
        std::printf("\n");
    }
}

int floor_study(FloorStudyOptions o)
{
    study_table(o, true);
    // The report's point: on a moving vehicle the same patch is scanned from several ranges.
    // Six nods at 1 m/s drive 30 m: the cells near the vehicle at the end were scanned on
    // every nod on the way, from 20 m down to 1 m.
    o.speed_mps = 1.0;
    o.nods = 6;
    study_table(o, false);
    return 0;
}

}  // namespace

int main(int argc, char** argv)
{
    CLI::App app{"ugv-eval: terrain maps against ground truth"};
    app.set_version_flag("--version", std::string("ugv-eval ") + UGV_VERSION);
    app.require_subcommand(1);
    auto* cmp = app.add_subcommand("compare", "the maps of a log against a height field");
    std::string log_path, channel = "TERRAIN_MAP";
    double flat = 0.0, obstacle_height = 0.2;
    std::vector<std::string> box_args;
    bool all = false;
    cmp->add_option("log", log_path, "LCM log with terrain_map_t")->required()->check(CLI::ExistingFile);
    cmp->add_option("--channel", channel, "channel of the maps");
    std::string truth_path;
    cmp->add_option("--truth", truth_path, "truth height field (ugv-sim world's truth.hf)")->check(CLI::ExistingFile);
    double edge_margin = 0.0;
    cmp->add_option("--exclude-edges", edge_margin,
                    "with --truth: leave out cells within this distance (m) of a step of more than 0.1 m in the "
                    "truth (a wall's face has no single height)")
        ->check(CLI::Range(0.0, 5.0));
    cmp->add_option("--flat", flat, "height of the ground (m, ENU up)");
    cmp->add_option("--box", box_args, "an obstacle: X0,Y0,X1,Y1,H (m, ENU)");
    cmp->add_option("--obstacle-height", obstacle_height,
                    "a cell standing this much above the lowest truth within --ground-radius is an obstacle (m)");
    double ground_radius = ugv::eval::TruthRules{}.step_radius_m;
    cmp->add_option("--ground-radius", ground_radius, "the local ground of a cell: the lowest truth within this (m)")
        ->check(CLI::Range(0.01, 5.0));
    cmp->add_flag("--all", all, "every map, not only the last");

    auto* cov = app.add_subcommand("coverage", "the known share of the area ahead of the vehicle, after a turn");
    std::string cov_log;
    CoverageOptions co;
    std::vector<double> ahead{co.area.x0_m, co.area.x1_m};
    cov->add_option("log", cov_log, "LCM log with terrain_map_t")->required()->check(CLI::ExistingFile);
    cov->add_option("--channel", co.channel, "channel of the maps");
    cov->add_option("--ahead", ahead, "the area from X0 to X1 metres ahead of the reference point (body frame)")
        ->expected(2)
        ->delimiter(',')
        ->check(CLI::Range(-100.0, 100.0));
    cov->add_option("--half-width", co.area.half_width_m, "... and this far either side of the centre line (m)")
        ->check(CLI::Range(0.1, 100.0));
    cov->add_option("--turn", co.turn_deg, "the turn: the first map this far (deg) from the first map's heading")
        ->check(CLI::Range(1.0, 180.0));
    cov->add_option("--window", co.window_s, "summarise the maps of this many seconds from the turn")
        ->check(CLI::Range(0.0, 3600.0));
    cov->add_flag("--all", co.all, "one JSON line per map before the summary");

    auto* study = app.add_subcommand("floor-study", "Tables 3 and 4 of the report on a simulated flat floor");
    FloorStudyOptions o;
    study->add_option("--trials", o.trials, "trials averaged")->check(CLI::Range(1, 1000));
    study->add_option("--seed", o.seed, "random seed");
    study->add_flag("--spread", o.spread, "spread points whose sigma exceeds the grid (section 3.5)");
    ugv::eval::MapDiffCommand diff(app);  // its options are bound to its members
    ugv::eval::TraverseScoreCommand traverse(app);
    ugv::eval::InterlaceCommand interlace(app);
    ugv::eval::AttitudeCommand attitude(app);
    CLI11_PARSE(app, argc, argv);

    if (diff.chosen()) return diff.run();
    if (traverse.chosen()) return traverse.run();
    if (interlace.chosen()) return interlace.run();
    if (*cov) {
        if (!(ahead[1] > ahead[0])) {
            std::fprintf(stderr, "ugv-eval: --ahead %g,%g: X1 must be greater than X0\n", ahead[0], ahead[1]);
            return 2;
        }
        co.area.x0_m = ahead[0];
        co.area.x1_m = ahead[1];
        return coverage(cov_log, co);
    }
    if (attitude.chosen()) return attitude.run();
    if (*cmp) {
        std::vector<Box> boxes;
        for (const std::string& s : box_args) {
            Box b{};
            if (std::sscanf(s.c_str(), "%lf,%lf,%lf,%lf,%lf", &b.x0, &b.y0, &b.x1, &b.y1, &b.h) != 5) {
                std::fprintf(stderr, "ugv-eval: --box %s: expected X0,Y0,X1,Y1,H\n", s.c_str());
                return 2;
            }
            boxes.push_back(b);
        }
        if (!truth_path.empty()) {
            std::ifstream in(truth_path, std::ios::binary);
            std::stringstream bytes;
            bytes << in.rdbuf();
            try {
                auto field = std::make_shared<ugv::simworld::HeightField>(ugv::simworld::decode_height_field(bytes.str()));
                const double step = field->resolution_m;
                auto truth = [field, edge_margin, step](double x, double y) {
                    const double z = field->height_at(x, y);
                    for (double dx = -edge_margin; dx <= edge_margin + 1e-9; dx += step)
                        for (double dy = -edge_margin; dy <= edge_margin + 1e-9; dy += step)
                            if (!(std::abs(field->height_at(x + dx, y + dy) - z) <= 0.1)) return std::numeric_limits<double>::quiet_NaN();
                    return z;
                };
                ugv::eval::TruthRules rules;
                rules.step_radius_m = ground_radius;
                auto terrain = std::make_shared<const ugv::eval::TruthTerrain>(field, rules);
                auto ground = [terrain](double x, double y) { return terrain->local_ground_at(x, y); };
                return compare(log_path, channel, truth, ground, obstacle_height, all);
            } catch (const std::invalid_argument& e) {
                std::fprintf(stderr, "ugv-eval: %s: %s\n", truth_path.c_str(), e.what());
                return 2;
            }
        }
        auto flat_with_boxes = [flat, boxes](double x, double y) {
            double z = flat;
            for (const Box& b : boxes)
                if (x >= b.x0 && x <= b.x1 && y >= b.y0 && y <= b.y1) z = std::max(z, b.h);
            return z;
        };
        // The lowest of the floor and boxes within the radius, on a 5 cm grid.
        auto ground = [flat_with_boxes, ground_radius](double x, double y) {
            const int n = static_cast<int>(std::floor(ground_radius / 0.05 + 1e-9));
            double low = flat_with_boxes(x, y);
            for (int a = -n; a <= n; ++a)
                for (int b = -n; b <= n; ++b)
                    if (a * a + b * b <= n * n) low = std::min(low, flat_with_boxes(x + 0.05 * a, y + 0.05 * b));
            return low;
        };
        return compare(log_path, channel, flat_with_boxes, ground, obstacle_height, all);
    }
    return floor_study(o);
}
