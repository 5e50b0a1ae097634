#include "nodscan_config.hpp"

#include <numbers>

#include "ugv/nodscan/mount_config.hpp"
#include "ugv/runtime/stamp_gate.hpp"

namespace ugv::nodscan_daemon {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

}  // namespace

NodscanConfig read_config(runtime::Config& cfg)
{
    NodscanConfig c;
    c.scan_channel = cfg.get_channel_regex("scan_channel", c.scan_channel);
    c.servo_channel = cfg.get_channel_regex("servo_channel", c.servo_channel);
    c.channel = cfg.get_channel("channel", c.channel);
    c.sensor_id = cfg.get_string("sensor_id", "");
    c.assembler.range_sigma_m = cfg.get_double("range_sigma_m", 0.01, 0.0, 1.0);
    c.assembler.angle_sigma_rad = cfg.get_double("angle_sigma_deg", 0.05, 0.0, 10.0) * kDeg;
    c.max_wait_us = cfg.get_int("max_wait_ms", 100, 0, 2000) * 1000;
    c.assembler.max_extrapolation_us = cfg.get_int("max_extrapolation_ms", 20, 0, 500) * 1000;
    c.servo_history_us = cfg.get_int("servo_history_ms", 2000, 100, 60000) * 1000;
    c.max_stamp_ahead_us = runtime::read_max_stamp_ahead_us(cfg);
    c.stamp_skew = runtime::read_stamp_skew_limits(cfg, c.max_stamp_ahead_us);
    runtime::Config m = cfg.section("mount");
    c.assembler.mount = nodscan::read_mount(m);
    if (c.servo_history_us < 2 * c.max_wait_us)
        cfg.fail("servo_history_ms", "must be at least twice max_wait_ms, or a waiting scan loses its angles");
    return c;
}

}  // namespace ugv::nodscan_daemon
