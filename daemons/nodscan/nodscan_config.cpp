#include "nodscan_config.hpp"

#include <numbers>

#include "ugv/runtime/stamp_gate.hpp"

namespace ugv::nodscan_daemon {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

Eigen::Vector3d vec3(const std::vector<double>& v, double scale = 1.0)
{
    return Eigen::Vector3d(v[0] * scale, v[1] * scale, v[2] * scale);
}

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
    c.assembler.mount.axis_xyz_m = vec3(m.get_doubles("tilt_axis_xyz_m", {0.0, 0.0, 0.87}, 3, -10.0, 10.0));
    c.assembler.mount.axis_rpy_rad = vec3(m.get_doubles("tilt_axis_rpy_deg", {0.0, 0.0, 0.0}, 3, -180.0, 180.0), kDeg);
    c.assembler.mount.laser_xyz_m = vec3(m.get_doubles("laser_xyz_m", {0.0, 0.0, 0.0}, 3, -2.0, 2.0));
    c.assembler.mount.laser_rpy_rad = vec3(m.get_doubles("laser_rpy_deg", {0.0, 0.0, 0.0}, 3, -180.0, 180.0), kDeg);
    if (c.servo_history_us < 2 * c.max_wait_us)
        cfg.fail("servo_history_ms", "must be at least twice max_wait_ms, or a waiting scan loses its angles");
    return c;
}

}  // namespace ugv::nodscan_daemon
