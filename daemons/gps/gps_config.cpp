#include "gps_config.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace ugv::gps_daemon {
namespace {

constexpr double kSilencePeriods = 5.0;  // "a few expected periods" of the fastest log
constexpr double kMinSilenceS = 0.5;

const std::initializer_list<int64_t> kBauds = {0, 4800, 9600, 19200, 38400, 57600, 115200, 230400, 460800, 921600};

}  // namespace

novatel::LogRequest parse_log_entry(const std::string& entry, double default_period_s)
{
    std::istringstream in(entry);
    novatel::LogRequest r;
    std::string extra;
    if (!(in >> r.message)) {
        throw std::invalid_argument("empty log entry");
    }
    for (auto& c : r.message) {
        if (!std::isalnum(static_cast<unsigned char>(c))) {
            throw std::invalid_argument("'" + entry + "': a log name is letters and digits");
        }
        c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    }
    r.period_s = default_period_s;
    if (in >> extra) {
        std::size_t used = 0;
        try {
            r.period_s = std::stod(extra, &used);
        } catch (const std::exception&) {
            used = 0;
        }
        if (used != extra.size() || !std::isfinite(r.period_s)) {
            throw std::invalid_argument("'" + entry + "': the period must be a number of seconds");
        }
    }
    if (r.period_s < 0.05 || r.period_s > 3600.0) {
        throw std::invalid_argument("'" + entry + "': period must be in [0.05, 3600] s");
    }
    if (in >> extra) {
        throw std::invalid_argument("'" + entry + "': expected \"NAME [PERIOD_S]\"");
    }
    return r;
}

GpsConfig read_config(runtime::Config& config)
{
    GpsConfig c;
    c.device = config.get_string("device", c.device);
    c.baud = static_cast<int>(config.get_int("baud", 9600, kBauds));
    if (c.baud == 0) {
        config.fail("baud", "must be a serial rate, not 0");
    }
    c.com_baud = static_cast<int>(config.get_int("com_baud", 0, kBauds));
    const std::string protocol = config.get_enum("protocol", "auto", {"auto", "novatel", "nmea"});
    c.protocol = protocol == "nmea" ? Protocol::nmea : protocol == "novatel" ? Protocol::novatel : Protocol::automatic;
    c.configure = config.get_enum("mode", "configure", {"configure", "passive"}) == "configure";
    const double period_s = config.get_double("period_s", 0.25, 0.05, 3600.0);
    const std::vector<std::string> default_logs =
        c.protocol == Protocol::nmea ? std::vector<std::string>{"GPGGA", "GPRMC", "GPGST"}
                                     : std::vector<std::string>{"BESTPOSB", "BESTVELB"};
    for (const auto& entry : config.get_strings("logs", default_logs)) {
        try {
            c.logs.push_back(parse_log_entry(entry, period_s));
        } catch (const std::invalid_argument& e) {
            config.fail("logs", e.what());
        }
    }
    if (c.configure && c.logs.empty()) {
        config.fail("logs", "configure mode needs at least one log");
    }
    c.channel_fix = config.get_channel("channel_fix", c.channel_fix);
    c.channel_vel = config.get_channel("channel_vel", c.channel_vel);
    c.channel_raw = config.get_channel("channel_raw", c.channel_raw);
    c.publish_raw = config.get_bool("publish_raw", false);
    c.leap_seconds = static_cast<int>(config.get_int("leap_seconds", 18, 0, 60));
    c.output_latency_us = std::llround(config.get_double("output_latency_ms", 0.0, 0.0, 1000.0) * 1000.0);
    c.reply_timeout_ms = static_cast<int>(config.get_int("reply_timeout_ms", 1000, 50, 10000));
    const double silence_s = config.get_double("silence_timeout_s", 0.0, 0.0, 600.0);
    double fastest = period_s;
    for (const auto& l : c.logs) {
        fastest = std::min(fastest, l.period_s);
    }
    c.silence_timeout_us = std::llround(
        (silence_s > 0 ? silence_s : std::max(kMinSilenceS, kSilencePeriods * fastest)) * 1e6);
    return c;
}

}  // namespace ugv::gps_daemon
