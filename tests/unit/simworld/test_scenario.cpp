#include <catch2/catch.hpp>

#include "ugv/simworld/scenario.hpp"

using namespace ugv::simworld;
using ugv::runtime::Config;
using ugv::runtime::ConfigError;

namespace {

// The one-line error parsing a scenario text gives, or "" when it parses.
std::string error(const std::string& text)
{
    try {
        Config c = Config::parse(text, "s.toml");
        parse_scenario(c);
    } catch (const ConfigError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("the default scenario is the report's demonstration")
{
    Config c = Config::parse(default_scenario_toml(), "default.toml");
    const Scenario s = parse_scenario(c);
    CHECK(s.name == "report-demo");
    REQUIRE(s.terrain.boxes.size() == 1);
    CHECK(s.terrain.walls.size() == 2);
    CHECK(s.terrain.ramps.size() == 1);
    CHECK(s.terrain.ditches.size() == 1);
    REQUIRE(s.path.segments.size() == 5);
    CHECK(s.path.segments[1].speed_mps == 3.0);
    CHECK(s.path.segments[2].kind == PathSegment::Kind::arc);
    CHECK(s.path.segments[2].turn_rad > 0);  // left
    REQUIRE(s.lasers.size() == 1);
    CHECK(s.lasers[0].name.empty());
    CHECK(s.lasers[0].suffix().empty());
    CHECK(s.lasers[0].mount.axis_xyz_m[2] == 0.87);
    CHECK(s.lasers[0].servo.counts_per_rad() == Approx(4096.0 * 50 / (2 * M_PI)));
}

TEST_CASE("a bad scenario value is one line FILE: KEY: why")
{
    CHECK(error("") == "");
    CHECK(error("[[segment]]\nkind = \"straight\"\nspeed_mps = 5.0\n") ==
          "s.toml: segment[0].speed_mps: 5 is out of range [0.01, 3]");
    CHECK(error("[[box]]\nx0 = 2.0\nx1 = 1.0\n") == "s.toml: box[0].x1: must be greater than x0");
    CHECK(error("[[segment]]\nkind = \"reverse\"\n") ==
          "s.toml: segment[0].kind: \"reverse\" is not one of \"straight\", \"arc\", \"stop\"");
    CHECK(error("[gps]\nantena_m = [0, 0, 1]\n") == "s.toml: gps.antena_m: unknown key");
}

TEST_CASE("a scenario without [[laser]] has today's one laser, its [laser] and [servo] read as before")
{
    Config c = Config::parse("[laser]\nlaser_xyz_m = [0.1, 0.0, 0.05]\nrange_noise_m = 0.02\n[servo]\nnode_id = 5\n",
                             "one.toml");
    const Scenario s = parse_scenario(c);
    REQUIRE(s.lasers.size() == 1);
    CHECK(s.lasers[0].name.empty());
    CHECK(s.lasers[0].mount.laser_xyz_m.x() == 0.1);
    CHECK(s.lasers[0].range_noise_m == 0.02);
    CHECK(s.lasers[0].servo.node_id == 5);
    Config none = Config::parse("", "none.toml");
    CHECK(parse_scenario(none).lasers.size() == 1);
}

TEST_CASE("[[laser]] tables: several lasers, each with its mount and its own servo")
{
    Config c = Config::parse(R"(
[[laser]]
name = "left"
tilt_axis_xyz_m = [0.0, 0.6, 0.87]
[laser.servo]
node_id = 1
[[laser]]
name = "right"
tilt_axis_xyz_m = [0.0, -0.6, 0.87]
range_noise_m = 0.03
[laser.servo]
node_id = 2
gear_ratio = 100
)",
                             "tandem.toml");
    const Scenario s = parse_scenario(c);
    REQUIRE(s.lasers.size() == 2);
    CHECK(s.lasers[0].name == "left");
    CHECK(s.lasers[0].suffix() == "-left");
    CHECK(s.lasers[0].mount.axis_xyz_m.y() == 0.6);
    CHECK(s.lasers[0].servo.node_id == 1);
    CHECK(s.lasers[0].range_noise_m == 0.01);  // default
    CHECK(s.lasers[1].name == "right");
    CHECK(s.lasers[1].mount.axis_xyz_m.y() == -0.6);
    CHECK(s.lasers[1].range_noise_m == 0.03);
    CHECK(s.lasers[1].servo.node_id == 2);
    CHECK(s.lasers[1].servo.gear_ratio == 100);
    CHECK(s.lasers[1].servo.counts_per_rev == 4096);  // default
}

TEST_CASE("a bad [[laser]] table is one line naming the laser's key")
{
    CHECK(error("[[laser]]\ntilt_axis_xyz_m = [0, 0, 1]\n") ==
          "s.toml: laser[0].name: is required in a [[laser]] table (e.g. \"left\")");
    CHECK(error("[[laser]]\nname = \"Left\"\n") ==
          "s.toml: laser[0].name: \"Left\" is not 1 to 16 lower-case letters and digits");
    CHECK(error("[[laser]]\nname = \"a\"\n[[laser]]\nname = \"a\"\n") == "s.toml: laser[1].name: \"a\" names two lasers");
    CHECK(error("[servo]\nnode_id = 2\n[[laser]]\nname = \"a\"\n") ==
          "s.toml: servo: with [[laser]] tables each laser has its own servo ([laser.servo] after its [[laser]])");
    CHECK(error("[[laser]]\nname = \"a\"\n[laser.servo]\nnode = 2\n") == "s.toml: laser[0].servo.node: unknown key");
    CHECK(error("[[laser]]\nname = \"a\"\n[laser.servo]\nnode_id = 200\n") ==
          "s.toml: laser[0].servo.node_id: 200 is out of range [1, 127]");
    CHECK(error("[[laser]]\nname = \"a\"\nlaser_xyz = [0, 0, 0]\n") == "s.toml: laser[0].laser_xyz: unknown key");
    std::string nine;
    for (int i = 0; i < 9; ++i) nine += "[[laser]]\nname = \"l" + std::to_string(i) + "\"\n";
    CHECK(error(nine) == "s.toml: laser: 9 lasers; at most 8");
}

TEST_CASE("the sensors' error models: ahrs and markov by default, each model's keys only with it")
{
    Config d = Config::parse(default_scenario_toml(), "default.toml");
    const Scenario s = parse_scenario(d);
    CHECK(s.imu.error_model == "ahrs");
    CHECK(s.imu.tilt_time_constant_s == 10.0);
    CHECK(s.imu.angle_sigma_deg == 0.047);
    CHECK(s.gps.error_model == "markov");
    CHECK(s.gps.rtk_fixed.sigma_m == 0.02);
    CHECK(s.gps.dgps.time_constant_s == 60.0);
    // "white": today's white angle noise by default.
    Config w = Config::parse("[imu]\nerror_model = \"white\"\n[gps]\nerror_model = \"white\"\n", "w.toml");
    const Scenario sw = parse_scenario(w);
    CHECK(sw.imu.angle_sigma_deg == 0.7);
    CHECK(sw.gps.error_model == "white");

    CHECK(error("[imu]\nerror_model = \"kalman\"\n") ==
          "s.toml: imu.error_model: \"kalman\" is not one of \"ahrs\", \"white\"");
    CHECK(error("[imu]\nerror_model = \"white\"\nmag_disturbance_deg = 2.0\n") ==
          "s.toml: imu.mag_disturbance_deg: only used with error_model = \"ahrs\" (remove it, or choose that model)");
    CHECK(error("[imu]\ntilt_time_constant_s = 0.0\n") == "s.toml: imu.tilt_time_constant_s: 0 is out of range [0.1, 1000]");
    CHECK(error("[imu]\ngyro_bias_walk_dps_per_sqrt_s = -1\n") ==
          "s.toml: imu.gyro_bias_walk_dps_per_sqrt_s: -1 is out of range [0, 1]");
    CHECK(error("[gps]\nerror_model = \"white\"\ndgps_time_constant_s = 30\n") ==
          "s.toml: gps.dgps_time_constant_s: only used with error_model = \"markov\" (remove it, or choose that model)");
    CHECK(error("[gps]\nrtk_float_sigma_m = 0\n") == "s.toml: gps.rtk_float_sigma_m: 0 is out of range [0.001, 100]");
    CHECK(error("[gps]\nsingle_time_constant_s = \"long\"\n").find("s.toml: gps.single_time_constant_s: ") == 0);
}

TEST_CASE("the configured mounts default to the true ones, and a scenario can set them apart")
{
    Config same = Config::parse("[laser]\ntilt_axis_rpy_deg = [1.5, -1.2, 0]\n[gps]\nantenna_m = [0.3, -0.1, 1.7]\n"
                                "[imu]\nmount_rpy_deg = [1, 2, 3]\n",
                                "same.toml");
    const Scenario s = parse_scenario(same);
    CHECK(s.lasers[0].configured_mount.axis_rpy_rad == s.lasers[0].mount.axis_rpy_rad);
    CHECK(s.lasers[0].mount.axis_rpy_rad.x() == Approx(1.5 * M_PI / 180));
    CHECK(s.gps.configured_antenna_m == s.gps.antenna_m);
    CHECK(s.imu.configured_mount_rpy_rad == s.imu.mount_rpy_rad);
    CHECK(s.imu.mount_rpy_rad.z() == Approx(3 * M_PI / 180));

    Config apart = Config::parse("[laser]\ntilt_axis_xyz_m = [0, 0, 0.95]\nconfigured_tilt_axis_xyz_m = [0, 0, 0.87]\n"
                                 "[gps]\nantenna_m = [0.3, -0.1, 1.7]\nconfigured_antenna_m = [0, 0, 1.7]\n"
                                 "[imu]\nmount_rpy_deg = [1, 2, 3]\nconfigured_mount_rpy_deg = [0, 0, 0]\n",
                                 "apart.toml");
    const Scenario t = parse_scenario(apart);
    CHECK(t.lasers[0].mount.axis_xyz_m.z() == 0.95);
    CHECK(t.lasers[0].configured_mount.axis_xyz_m.z() == 0.87);
    CHECK(t.gps.antenna_m.x() == 0.3);
    CHECK(t.gps.configured_antenna_m.x() == 0.0);
    CHECK(t.imu.configured_mount_rpy_rad.isZero());
    CHECK_THAT(error("[gps]\nconfigured_antenna_m = [0, 0]\n"), Catch::Contains("configured_antenna_m"));
    CHECK_THAT(error("[imu]\nconfigured_mount_rpy_deg = [0, 0, 200]\n"), Catch::Contains("configured_mount_rpy_deg"));
}
