#include "pose_config.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "ugv/runtime/stamp_gate.hpp"

namespace ugv::pose_daemon {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

estimation::FixQuality read_quality(runtime::Config& cfg, const std::string& key, const char* def)
{
    const std::string q = cfg.get_enum(key, def, {"single", "sbas", "dgps", "rtk_float", "rtk_fixed"});
    if (q == "single") return estimation::FixQuality::single;
    if (q == "sbas") return estimation::FixQuality::sbas;
    if (q == "dgps") return estimation::FixQuality::dgps;
    if (q == "rtk_float") return estimation::FixQuality::rtk_float;
    return estimation::FixQuality::rtk_fixed;
}

int64_t seconds_to_us(double s)
{
    return static_cast<int64_t>(std::llround(s * 1e6));
}

// `datum = "first_fix"` or `[datum] lat = .., lon = .., height = ..`.
void read_datum(runtime::Config& cfg, estimation::EstimatorConfig& est)
{
    bool is_table = false;
    try {
        const std::string mode = cfg.get_string("datum", "first_fix");
        if (mode != "first_fix") {
            cfg.fail("datum", "must be \"first_fix\" or a table with lat, lon, height");
        }
    } catch (const runtime::ConfigError& e) {
        if (e.key() != "datum" || !cfg.has("datum") || e.why().find("must be a string") == std::string::npos) {
            throw;
        }
        is_table = true;
    }
    if (!is_table) {
        est.datum.reset();
        return;
    }
    runtime::Config d = cfg.section("datum");
    for (const char* k : {"lat", "lon", "height"}) {
        if (!d.has(k)) {
            d.fail(k, "required when datum is a table");
        }
    }
    est.datum = estimation::Datum{d.get_double("lat", 0.0, -90.0, 90.0), d.get_double("lon", 0.0, -180.0, 180.0),
                                  d.get_double("height", 0.0, -1000.0, 10000.0)};
}

}  // namespace

PoseConfig read_config(runtime::Config& cfg)
{
    PoseConfig c;
    estimation::EstimatorConfig& e = c.estimator;
    read_datum(cfg, e);
    e.datum_min_quality = read_quality(cfg, "datum_min_quality", "single");
    e.min_fix_quality = read_quality(cfg, "min_fix_quality", "single");

    // "imu": a pose right after each IMU sample (at most rate_hz), the freshest state;
    // "grid": at each multiple of the period, by prediction.
    e.pose_times = cfg.get_enum("pose_times", "imu", {"imu", "grid"}) == "imu" ? estimation::PoseTimes::imu
                                                                                : estimation::PoseTimes::grid;
    const double rate_hz = cfg.get_double("rate_hz", 100.0, 0.1, 100.0);
    e.output_period_us = static_cast<int64_t>(std::llround(1e6 / rate_hz));
    // Late inputs (a NovAtel velocity arrives ~0.34 s after its stamp on a 9600-baud line) are
    // applied from the history; a reorder window would only delay every pose by its length.
    e.buffer_us = seconds_to_us(cfg.get_double("buffer_s", 0.0, 0.0, 2.0));
    e.history_size = static_cast<std::size_t>(cfg.get_int("history_size", 100, 0, 10'000));
    e.max_ahead_us = seconds_to_us(cfg.get_double("max_ahead_of_newest_s", 0.5, 0.001, 3600.0));

    c.max_stamp_ahead_us = runtime::read_max_stamp_ahead_us(cfg);
    c.stamp_skew = runtime::read_stamp_skew_limits(cfg, c.max_stamp_ahead_us);
    // Older than this is older than anything the filter can still use (the history spans
    // ~1-2 s of inputs), with room for delivery (batching, a busy CPU).
    c.max_stamp_age_us = seconds_to_us(cfg.get_double("max_stamp_age_s", 2.0, 0.01, 3600.0));
    if (c.max_stamp_age_us < e.buffer_us) cfg.fail("max_stamp_age_s", "must be at least buffer_s");

    c.gps_fix_channel = cfg.get_channel_regex("gps_fix_channel", c.gps_fix_channel);
    c.gps_velocity_channel = cfg.get_channel_regex("gps_velocity_channel", c.gps_velocity_channel);
    c.imu_channel = cfg.get_channel_regex("imu_channel", c.imu_channel);
    c.channel = cfg.get_channel("channel", c.channel);

    e.process.accel = cfg.get_double("accel_noise", 0.1, 1e-6, 100.0);
    e.process.gyro = cfg.get_double("gyro_noise", 0.005, 1e-7, 10.0);
    e.process.heading_offset = cfg.get_double("heading_offset_noise", 1e-4, 1e-9, 1.0);
    e.process.gyro_bias = cfg.get_double("gyro_bias_noise", 1e-5, 1e-9, 1.0);
    e.initial_gyro_bias_sigma_rps = cfg.get_double("initial_gyro_bias_sigma_dps", 0.5, 0.001, 90.0) * kDeg;
    e.imu_orientation_sigma_rad = cfg.get_double("imu_orientation_sigma_deg", 2.0, 0.001, 90.0) * kDeg;
    e.imu_tilt_time_constant_s = cfg.get_double("imu_tilt_time_constant_s", 10.0, 0.0, 1000.0);
    e.imu_tilt_accel_factor = cfg.get_double("imu_tilt_accel_factor", 1.0, 0.0, 100.0);
    e.imu_yaw_time_constant_s = cfg.get_double("imu_yaw_time_constant_s", 0.0, 0.0, 1000.0);
    e.gps_default_sigma_m = cfg.get_double("gps_default_sigma_m", 5.0, 0.001, 1000.0);
    e.gps_min_sigma_m = cfg.get_double("gps_min_sigma_m", 0.01, 0.0001, 100.0);
    e.gps_velocity_sigma_mps = cfg.get_double("gps_velocity_sigma_mps", 0.1, 0.001, 100.0);
    e.course_min_speed_mps = cfg.get_double("course_min_speed_mps", 1.0, 0.01, 100.0);
    e.course_sigma_rad = cfg.get_double("course_sigma_deg", 3.0, 0.01, 90.0) * kDeg;
    const std::vector<double> antenna = cfg.get_doubles("gps_antenna_m", {0.0, 0.0, 0.0}, 3, -20.0, 20.0);
    e.gps_antenna_body_m = Eigen::Vector3d(antenna[0], antenna[1], antenna[2]);

    e.gate_position_chi2 = cfg.get_double("gate_position_chi2", 16.27, 0.1, 1e6);
    e.gate_velocity_chi2 = cfg.get_double("gate_velocity_chi2", 16.27, 0.1, 1e6);
    e.gate_orientation_chi2 = cfg.get_double("gate_orientation_chi2", 16.27, 0.1, 1e6);
    e.gate_course_chi2 = cfg.get_double("gate_course_chi2", 10.83, 0.1, 1e6);

    e.gps_timeout_us = seconds_to_us(cfg.get_double("gps_timeout_s", 1.0, 0.01, 60.0));
    e.imu_timeout_us = seconds_to_us(cfg.get_double("imu_timeout_s", 0.5, 0.01, 60.0));
    e.gps_reset_after_us = seconds_to_us(cfg.get_double("gps_reset_after_s", 10.0, 0.1, 3600.0));
    e.initial_velocity_sigma_mps = cfg.get_double("initial_velocity_sigma_mps", 1.0, 0.001, 100.0);
    e.initial_heading_sigma_rad = cfg.get_double("initial_heading_sigma_deg", 30.0, 0.1, 180.0) * kDeg;

    try {
        e.validate();
    } catch (const std::invalid_argument& ex) {
        cfg.fail("-", ex.what());
    }
    return c;
}

}  // namespace ugv::pose_daemon
