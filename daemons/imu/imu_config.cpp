#include "imu_config.hpp"

#include <cmath>

namespace ugv::imu_daemon {

namespace {
constexpr double deg = 3.14159265358979323846 / 180.0;
}

ImuConfig read_config(runtime::Config& cfg)
{
    ImuConfig c;
    c.device = cfg.get_string("device", c.device);
    c.baud = static_cast<int>(cfg.get_int("baud", 38400, {9600, 19200, 38400, 57600, 115200}));
    // Data commands worth streaming: orientation (Euler, quaternion, matrix) and/or vectors.
    c.session.command = static_cast<uint8_t>(
        cfg.get_int("command", 0x31, {0x02, 0x03, 0x04, 0x05, 0x0A, 0x0B, 0x0C, 0x0D, 0x0E, 0x31}));
    c.session.continuous = cfg.get_enum("mode", "continuous", {"continuous", "poll"}) == "continuous";
    c.session.poll_rate_hz = cfg.get_double("poll_rate_hz", 50.0, 1.0, 200.0);
    c.session.baud = c.baud;
    c.session.reply_timeout_ms = static_cast<int>(cfg.get_int("reply_timeout_ms", 300, 20, 5000));
    c.session.silence_timeout_ms = static_cast<int>(cfg.get_int("silence_timeout_ms", 1000, 100, 60000));
    c.session.latency_us = static_cast<int64_t>(std::llround(cfg.get_double("latency_ms", 0.0, 0.0, 1000.0) * 1000.0));
    c.channel = cfg.get_channel("channel", c.channel);
    c.publish_raw = cfg.get_bool("publish_raw", false);
    c.raw_channel = cfg.get_channel("raw_channel", c.raw_channel);
    c.orientation_sigma_rad = cfg.get_double("orientation_sigma_deg", 2.0, 0.0, 90.0) * deg;
    const auto rpy = cfg.get_doubles("mount_rpy_deg", {0.0, 0.0, 0.0}, 3, -180.0, 180.0);
    c.r_body_sensor = microstrain_gx1::rotation_from_euler(rpy[0] * deg, rpy[1] * deg, rpy[2] * deg);
    c.declination_rad = cfg.get_double("magnetic_declination_deg", 0.0, -180.0, 180.0) * deg;
    return c;
}

}  // namespace ugv::imu_daemon
