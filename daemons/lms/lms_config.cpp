#include "lms_config.hpp"

#include <cctype>
#include <cmath>
#include <stdexcept>

namespace ugv::lms_daemon {

namespace {

// A channel name (Config::get_channel's checks) in UPPER_SNAKE, as the lms page asks.
std::string channel_name(runtime::Config& cfg, const std::string& key, const std::string& def)
{
    std::string v = cfg.get_channel(key, def);
    for (const char c : v)
        if (!(std::isupper(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '_' || c == '.'))
            cfg.fail(key, "'" + v + "' is not an UPPER_SNAKE channel name");
    return v;
}

}  // namespace

LmsConfig read_config(runtime::Config& cfg)
{
    LmsConfig c;
    sick_lms2xx::SessionConfig& s = c.session;
    c.device = cfg.get_string("device", c.device);
    if (c.device.empty()) cfg.fail("device", "must not be empty");
    s.baud = static_cast<int>(cfg.get_int("baud", 500000, {9600, 19200, 38400, 500000}));
    s.angle_deg = static_cast<int>(cfg.get_int("angle_deg", 180, {100, 180}));
    const double res = cfg.get_double("resolution_deg", 0.5, 0.25, 1.0);
    s.resolution_cdeg = static_cast<int>(std::lround(res * 100.0));
    if (std::abs(res * 100.0 - s.resolution_cdeg) > 1e-6 ||
        (s.resolution_cdeg != 25 && s.resolution_cdeg != 50 && s.resolution_cdeg != 100))
        cfg.fail("resolution_deg", "must be 0.25, 0.5 or 1.0");
    if (s.resolution_cdeg == 25 && s.angle_deg != 100) cfg.fail("resolution_deg", "0.25 deg needs angle_deg = 100");
    s.units = cfg.get_enum("units", "mm", {"mm", "cm"}) == "mm" ? sick_lms2xx::Units::mm : sick_lms2xx::Units::cm;
    s.scan_index = cfg.get_bool("scan_index", false);
    s.beam_timing = cfg.get_enum("beam_timing", "interlaced", {"interlaced", "linear"}) == "linear"
                        ? sick_lms2xx::BeamTiming::linear
                        : sick_lms2xx::BeamTiming::interlaced;
    s.sweep_order = cfg.get_string("sweep_order", "");
    try {
        (void)sick_lms2xx::parse_sweep_order(s.sweep_order, s.resolution_cdeg);
    } catch (const std::invalid_argument& e) {
        cfg.fail("sweep_order", e.what());
    }
    s.password = cfg.get_string("password", "SICK_LMS");
    if (s.password.size() != 8) cfg.fail("password", "must be exactly 8 characters");
    s.stop_on_exit = cfg.get_bool("stop_on_exit", true);
    s.reply_timeout_ms = static_cast<int>(cfg.get_int("reply_timeout_ms", 300, 20, 5000));
    s.attempts = static_cast<int>(cfg.get_int("attempts", 3, 1, 20));
    s.silence_periods = static_cast<int>(cfg.get_int("silence_periods", 5, 2, 1000));
    c.channel = channel_name(cfg, "channel", c.channel);
    c.raw_channel = channel_name(cfg, "raw_channel", c.raw_channel);
    c.sensor_id = cfg.get_string("sensor_id", c.sensor_id);
    if (c.sensor_id.empty()) cfg.fail("sensor_id", "must not be empty");
    c.publish_raw = cfg.get_bool("publish_raw", false);
    return c;
}

}  // namespace ugv::lms_daemon
