#include <catch2/catch.hpp>

#include "ugv/simworld/scenario.hpp"

using namespace ugv::simworld;
using ugv::runtime::Config;
using ugv::runtime::ConfigError;

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
    auto error = [](const std::string& text) -> std::string {
        try {
            Config c = Config::parse(text, "s.toml");
            parse_scenario(c);
        } catch (const ConfigError& e) {
            return e.what();
        }
        return "";
    };
    CHECK(error("") == "");
    CHECK(error("[[segment]]\nkind = \"straight\"\nspeed_mps = 5.0\n") ==
          "s.toml: segment[0].speed_mps: 5 is out of range [0.01, 3]");
    CHECK(error("[[box]]\nx0 = 2.0\nx1 = 1.0\n") == "s.toml: box[0].x1: must be greater than x0");
    CHECK(error("[[segment]]\nkind = \"reverse\"\n") ==
          "s.toml: segment[0].kind: \"reverse\" is not one of \"straight\", \"arc\", \"stop\"");
    CHECK(error("[gps]\nantena_m = [0, 0, 1]\n") == "s.toml: gps.antena_m: unknown key");
}
