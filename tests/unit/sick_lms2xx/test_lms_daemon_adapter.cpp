// The ugv-lms adapter pieces: config keys (defaults, values, refusals) and the StampedScan ->
// laser_scan_t conversion.
#include <catch2/catch.hpp>

#include <cmath>

#include "lms_config.hpp"
#include "lms_messages.hpp"

using namespace ugv::lms_daemon;
using ugv::runtime::Config;
using ugv::runtime::ConfigError;

TEST_CASE("lms config: defaults", "[lms][daemon]")
{
    Config cfg = Config::empty();
    const LmsConfig c = read_config(cfg);
    CHECK(c.device == "/dev/ugv/lms");
    CHECK(c.channel == "LMS_SCAN");
    CHECK(c.raw_channel == "RAW_LMS");
    CHECK(c.sensor_id == "lms");
    CHECK_FALSE(c.publish_raw);
    CHECK(c.session.baud == 500000);
    CHECK(c.session.angle_deg == 180);
    CHECK(c.session.resolution_cdeg == 50);
    CHECK(c.session.units == ugv::sick_lms2xx::Units::mm);
    CHECK(c.session.stop_on_exit);
    CHECK_FALSE(c.session.scan_index);
    CHECK(c.session.password == "SICK_LMS");
    CHECK(c.session.beam_timing == ugv::sick_lms2xx::BeamTiming::interlaced);
    CHECK(c.session.sweep_order.empty());
}

TEST_CASE("lms config: every key read", "[lms][daemon]")
{
    Config cfg = Config::parse("device = \"/dev/ttyUSB3\"\nbaud = 38400\nangle_deg = 100\nresolution_deg = 0.25\n"
                               "units = \"cm\"\nscan_index = true\nstop_on_exit = false\nchannel = \"LMS_FRONT\"\n"
                               "raw_channel = \"RAW_LMS_FRONT\"\npublish_raw = true\nsensor_id = \"front\"\n"
                               "reply_timeout_ms = 500\nattempts = 5\nsilence_periods = 8\n"
                               "beam_timing = \"linear\"\nsweep_order = \"3102\"\n",
                               "lms.toml");
    const LmsConfig c = read_config(cfg);
    CHECK_NOTHROW(cfg.finish());
    CHECK(c.device == "/dev/ttyUSB3");
    CHECK(c.session.baud == 38400);
    CHECK(c.session.angle_deg == 100);
    CHECK(c.session.resolution_cdeg == 25);
    CHECK(c.session.units == ugv::sick_lms2xx::Units::cm);
    CHECK(c.session.scan_index);
    CHECK_FALSE(c.session.stop_on_exit);
    CHECK(c.channel == "LMS_FRONT");
    CHECK(c.raw_channel == "RAW_LMS_FRONT");
    CHECK(c.publish_raw);
    CHECK(c.sensor_id == "front");
    CHECK(c.session.reply_timeout_ms == 500);
    CHECK(c.session.attempts == 5);
    CHECK(c.session.silence_periods == 8);
    CHECK(c.session.beam_timing == ugv::sick_lms2xx::BeamTiming::linear);
    CHECK(c.session.sweep_order == "3102");
}

TEST_CASE("lms config: refusals name the key and why", "[lms][daemon]")
{
    const auto refused = [](const std::string& text, const std::string& key, const std::string& why) {
        Config cfg = Config::parse(text, "lms.toml");
        try {
            read_config(cfg);
            FAIL("accepted: " << text);
        } catch (const ConfigError& e) {
            CHECK(e.key() == key);
            if (!why.empty()) CHECK(e.why() == why);
        }
    };
    refused("resolution_deg = 0.3\n", "resolution_deg", "must be 0.25, 0.5 or 1.0");
    refused("resolution_deg = 0.25\n", "resolution_deg", "0.25 deg needs angle_deg = 100");
    refused("password = \"short\"\n", "password", "must be exactly 8 characters");
    refused("channel = \"lms\"\n", "channel", "'lms' is not an UPPER_SNAKE channel name");
    refused("device = \"\"\n", "device", "must not be empty");
    refused("baud = 57600\n", "baud", "");
    refused("angle_deg = 90\n", "angle_deg", "");
    refused("units = \"m\"\n", "units", "");
    refused("beam_timing = \"mirror\"\n", "beam_timing", "");
    refused("sweep_order = \"0123\"\n", "sweep_order",
            "\"0123\" has 4 digits; a 0.5 deg scan has 2 sweeps (e.g. \"01\" or \"10\")");
    refused("sweep_order = \"00\"\n", "sweep_order",
            "\"00\" is not an order of the beam phases 0..1, each once (e.g. \"01\" or \"10\")");
}

TEST_CASE("StampedScan -> laser_scan_t", "[lms][daemon]")
{
    ugv::sick_lms2xx::StampedScan s;
    s.scan.ranges_m = {1.5f, NAN, 2.25f};
    s.scan.flags = {0, 2, 0};
    s.scan.scan_index = 17;
    s.first_beam_utime = 1'700'000'000'123'456;
    s.time_increment_s = 0.001;
    s.scan_period_s = 0.02;
    s.angle_min_rad = -0.5;
    s.angle_increment_rad = 0.25;
    s.range_max_m = 8.182;
    s.sweep_period_s = 1.0 / 75.0;
    s.sweep_order = ugv::sick_lms2xx::parse_sweep_order("10", 50);
    const ugv::laser_scan_t m = to_message(s, "front", 42);
    CHECK(m.utime == 1'700'000'000'123'456);
    CHECK(m.seq == 42);
    CHECK(m.sensor_id == "front");
    CHECK(m.nranges == 3);
    CHECK(m.ranges[0] == 1.5f);
    CHECK(std::isnan(m.ranges[1]));
    CHECK(m.flags[1] == ugv::laser_scan_t::FLAG_DAZZLE);
    CHECK(m.device_scan_counter == 17);
    CHECK(m.angle_min == -0.5f);
    CHECK(m.angle_increment == 0.25f);
    CHECK(m.time_increment == Approx(0.001f));
    CHECK(m.scan_period == Approx(0.02f));
    CHECK(m.range_max == Approx(8.182f));
    CHECK(m.nsweeps == 2);
    CHECK(m.sweep_order == std::vector<int8_t>{1, 0});
    CHECK(m.sweep_period == Approx(1.0f / 75.0f));
    // It encodes (the array sizes agree with nranges).
    std::vector<uint8_t> buf(static_cast<std::size_t>(m.getEncodedSize()));
    CHECK(m.encode(buf.data(), 0, static_cast<int>(buf.size())) == static_cast<int>(buf.size()));
}
