// ugv-gps key validation (daemons/gps/gps_config.cpp).
#include <catch2/catch.hpp>

#include "gps_config.hpp"

using ugv::gps_daemon::parse_log_entry;
using ugv::gps_daemon::read_config;
using ugv::runtime::Config;
using ugv::runtime::ConfigError;

TEST_CASE("gps config: defaults")
{
    Config cfg = Config::empty();
    const auto c = read_config(cfg);
    CHECK(c.device == "/dev/ugv/gps");
    CHECK(c.baud == 9600);
    CHECK(c.configure);
    REQUIRE(c.logs.size() == 2);
    CHECK(c.logs[0].message == "BESTPOSB");
    CHECK(c.logs[0].period_s == 0.25);
    CHECK(c.logs[1].message == "BESTVELB");
    CHECK(c.leap_seconds == 18);
    CHECK(c.silence_timeout_us == 1'250'000);  // 5 x 0.25 s
    CHECK(c.channel_fix == "GPS_FIX");
    CHECK(c.channel_vel == "GPS_VEL");
    CHECK_FALSE(c.publish_raw);
}

TEST_CASE("gps config: NMEA defaults, per-log periods and the automatic silence timeout")
{
    Config cfg = Config::parse("protocol = \"nmea\"\nperiod_s = 0.5\n");
    auto c = read_config(cfg);
    REQUIRE(c.logs.size() == 3);
    CHECK(c.logs[0].message == "GPGGA");
    CHECK(c.logs[2].message == "GPGST");
    CHECK(c.logs[2].period_s == 0.5);
    Config cfg2 = Config::parse("logs = [\"bestposb 0.05\", \"timeb 1\"]\nsilence_timeout_s = 3\n");
    c = read_config(cfg2);
    CHECK(c.logs[0].message == "BESTPOSB");
    CHECK(c.logs[0].period_s == 0.05);
    CHECK(c.logs[1].period_s == 1.0);
    CHECK(c.silence_timeout_us == 3'000'000);
    Config cfg3 = Config::parse("logs = [\"bestposb 0.05\"]\n");
    CHECK(read_config(cfg3).silence_timeout_us == 500'000);  // at least 0.5 s
}

TEST_CASE("gps config: bad values name the key")
{
    const auto key_of = [](const std::string& text) {
        Config cfg = Config::parse(text, "gps.toml");
        try {
            read_config(cfg);
        } catch (const ConfigError& e) {
            return e.key();
        }
        return std::string("(accepted)");
    };
    CHECK(key_of("baud = 12345\n") == "baud");
    CHECK(key_of("mode = \"active\"\n") == "mode");
    CHECK(key_of("protocol = \"ubx\"\n") == "protocol");
    CHECK(key_of("logs = [\"BESTPOSB fast\"]\n") == "logs");
    CHECK(key_of("logs = [\"BESTPOSB 0.01\"]\n") == "logs");
    CHECK(key_of("logs = [\"BEST-POS\"]\n") == "logs");
    CHECK(key_of("logs = []\n") == "logs");
    CHECK(key_of("leap_seconds = 99\n") == "leap_seconds");
    CHECK(key_of("mode = \"passive\"\nlogs = []\n") == "(accepted)");
}

TEST_CASE("parse_log_entry")
{
    const auto r = parse_log_entry("  bestvelb   0.2 ", 1.0);
    CHECK(r.message == "BESTVELB");
    CHECK(r.period_s == 0.2);
    CHECK(parse_log_entry("gpgga", 0.5).period_s == 0.5);
    CHECK_THROWS_AS(parse_log_entry("bestposb 1 2", 1.0), std::invalid_argument);
    CHECK_THROWS_AS(parse_log_entry("", 1.0), std::invalid_argument);
}
