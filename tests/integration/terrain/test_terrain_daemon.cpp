// ugv-terrain end to end: --replay of a synthetic drive, twice, gives identical maps; the
// published terrain_map_t decodes with the generated class and shows the box where it is.
#include <catch2/catch.hpp>

#include <lcm/lcm-cpp.hpp>

#include <cmath>
#include <string>
#include <vector>

#include <ugv/terrain_map_t.hpp>

#include "synthetic_log.hpp"
#include "ugv_test/process.hpp"

using namespace ugv;

namespace {

std::vector<std::vector<uint8_t>> events_on(const std::string& path, const std::string& channel)
{
    std::vector<std::vector<uint8_t>> out;
    lcm::LogFile log(path, "r");
    REQUIRE(log.good());
    while (const lcm::LogEvent* ev = log.readNextEvent()) {
        if (ev->channel != channel) continue;
        const auto* p = static_cast<const uint8_t*>(ev->data);
        out.emplace_back(p, p + ev->datalen);
    }
    return out;
}

// The cell of map m that holds body-frame point (bx, by), or -1.
long cell_of(const terrain_map_t& m, double bx, double by)
{
    // The map's axes are the body's turned by -residual_yaw: map = R(residual_yaw) body.
    const double c = std::cos(m.residual_yaw), s = std::sin(m.residual_yaw);
    const double mx = c * bx - s * by, my = s * bx + c * by;
    const long i = static_cast<long>(std::floor((mx - m.origin_x) / m.resolution));
    const long j = static_cast<long>(std::floor((my - m.origin_y) / m.resolution));
    if (i < 0 || j < 0 || i >= m.nx || j >= m.ny) return -1;
    return i * m.ny + j;
}

}  // namespace

TEST_CASE("ugv-terrain --replay is deterministic and its map shows the box")
{
    test::TempDir dir;
    test::SyntheticDrive drive;
    const std::string in = dir / "drive.log";
    drive.write_log(in);
    const std::string config = dir / "terrain.toml";
    test::write_file(config, "publish_hz = 5.0\ntheta_d_deg = 5.0\nstatistics = \"variance_weighted\"\n");

    for (const char* out : {"maps1.log", "maps2.log"}) {
        const int rc = test::run({test::bin("ugv-terrain"), "--config", config, "--replay", in, "--out", dir / out},
                                 dir / "stdout.txt", dir / "stderr.txt", 60.0);
        INFO(test::read_file(dir / "stderr.txt"));
        REQUIRE(rc == 0);
    }
    const auto first = events_on(dir / "maps1.log", "TERRAIN_MAP");
    const auto second = events_on(dir / "maps2.log", "TERRAIN_MAP");
    // 5 s at 5 Hz of message time: 25 or 26 maps depending on the first slot.
    CHECK(first.size() >= 25);
    CHECK(first.size() <= 26);
    REQUIRE(first.size() == second.size());
    for (std::size_t k = 0; k < first.size(); ++k) CHECK(first[k] == second[k]);

    terrain_map_t map;
    REQUIRE(map.decode(first.back().data(), 0, static_cast<int>(first.back().size())) ==
            static_cast<int>(first.back().size()));
    CHECK(map.nx == 150);
    CHECK(map.ny == 150);
    CHECK(map.ncells == 150 * 150);
    CHECK(map.resolution == Approx(0.2f));
    CHECK(map.mode == terrain_map_t::MODE_EGOCENTRIC);
    CHECK(map.statistics == terrain_map_t::STATS_VARIANCE_WEIGHTED);
    CHECK(map.seq == static_cast<int64_t>(first.size()) - 1);
    CHECK(std::abs(map.residual_yaw) < 5.0 * M_PI / 180.0 + 1e-6);
    // The map refers to the pose it was published with.
    CHECK(map.utime == map.pose.utime);
    const double t = static_cast<double>(map.pose.utime - drive.start_utime) * 1e-6;
    const Eigen::Vector3d pose = drive.pose_at(t);
    CHECK(map.pose.position[0] == Approx(pose.x()));
    // The box centre (8.2, 1.0) in the body frame of that pose.
    const double dx = 8.2 - pose.x(), dy = 1.0 - pose.y();
    const double bx = std::cos(pose.z()) * dx + std::sin(pose.z()) * dy;
    const double by = -std::sin(pose.z()) * dx + std::cos(pose.z()) * dy;
    const long box = cell_of(map, bx, by);
    REQUIRE(box >= 0);
    CHECK(map.mean_z[static_cast<std::size_t>(box)] == Approx(0.5f).margin(0.02));
    CHECK(map.count[static_cast<std::size_t>(box)] > 0);
    // Flat ground 2 m to the side of the box is at 0.
    const long ground = cell_of(map, bx + 2.0, by - 2.0);
    REQUIRE(ground >= 0);
    CHECK(map.mean_z[static_cast<std::size_t>(ground)] == Approx(0.0f).margin(0.02));
    // Rows behind the reference point were never mapped: the map's first row starts there.
    CHECK(map.origin_x == Approx(-0.5f - map.x_curr).margin(0.05));
    int known = 0;
    for (float z : map.mean_z) known += std::isnan(z) ? 0 : 1;
    CHECK(known > 1000);
    // The highest and lowest sample of each cell: NaN exactly where the mean is, around it
    // elsewhere; the box's top is its highest sample.
    REQUIRE(map.max_z.size() == map.mean_z.size());
    REQUIRE(map.min_z.size() == map.mean_z.size());
    int bracketed = 0;
    for (std::size_t k = 0; k < map.mean_z.size(); ++k) {
        CHECK(std::isnan(map.max_z[k]) == std::isnan(map.mean_z[k]));
        CHECK(std::isnan(map.min_z[k]) == std::isnan(map.mean_z[k]));
        bracketed += map.min_z[k] <= map.mean_z[k] + 1e-5f && map.mean_z[k] <= map.max_z[k] + 1e-5f ? 1 : 0;
    }
    CHECK(bracketed == known);
    CHECK(map.max_z[static_cast<std::size_t>(box)] == Approx(0.5f).margin(0.02));
    // Each cell's age: NaN exactly where the mean is; never negative nor older than the
    // drive. The laser's line of the last publish period (0.2 s: five clouds, each about 60
    // cells across) is younger than the period; what it swept seconds ago is as old.
    REQUIRE(map.age_s.size() == map.mean_z.size());
    const double period_s = 0.2, driven_s = t;
    int recent = 0, old = 0, in_range = 0;
    for (std::size_t k = 0; k < map.mean_z.size(); ++k) {
        CHECK(std::isnan(map.age_s[k]) == std::isnan(map.mean_z[k]));
        if (std::isnan(map.age_s[k])) continue;
        in_range += map.age_s[k] >= 0.0f && map.age_s[k] <= driven_s + 1e-3 ? 1 : 0;
        recent += map.age_s[k] <= period_s ? 1 : 0;
        old += map.age_s[k] > 1.0f ? 1 : 0;
    }
    CHECK(in_range == known);
    CHECK(recent >= 50);
    CHECK(old > 100);
}

TEST_CASE("ugv-terrain refuses a bad key with one line and exit status 2")
{
    // A value out of range, a spreading form that does not exist, and the older key against
    // another form.
    const auto [line, key] = GENERATE(table<std::string, std::string>(
        {{"publish_hz = 50.0", "publish_hz"},
         {"spread_form = \"levels\"", "spread_form"},
         {"spread_exact = true\nspread_form = \"centred\"", "spread_exact"}}));
    test::TempDir dir;
    const std::string config = dir / "terrain.toml";
    test::write_file(config, line + "\n");
    test::SyntheticDrive drive;
    drive.duration_s = 0.5;
    drive.write_log(dir / "drive.log");
    const int rc = test::run({test::bin("ugv-terrain"), "--config", config, "--replay", dir / "drive.log", "--out",
                              dir / "out.log"},
                             dir / "stdout.txt", dir / "stderr.txt", 30.0);
    CHECK(rc == 2);
    CHECK(test::read_file(dir / "stderr.txt").find(key) != std::string::npos);
}
