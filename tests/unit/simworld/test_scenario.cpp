#include <catch2/catch.hpp>

#include "ugv/simworld/scenario.hpp"

using namespace ugv::simworld;
using ugv::runtime::Config;
using ugv::runtime::ConfigError;

namespace {

// The one-line error a scenario text gives, or "" when it parses.
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
    CHECK(s.laser.mount.axis_xyz_m[2] == 0.87);
    CHECK(s.servo.counts_per_rad() == Approx(4096.0 * 50 / (2 * M_PI)));
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
