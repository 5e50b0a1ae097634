#include "antenna_command.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "log_events.hpp"
#include "report.hpp"
#include "ugv/bus/typed.hpp"
#include "ugv/geometry/rotation.hpp"
#include "ugv/gps_velocity_t.hpp"
#include "ugv/imu_t.hpp"
#include "ugv/runtime/config.hpp"

namespace ugv::calibrate_tool {

AntennaCommand::AntennaCommand(CLI::App& app)
    : sub_(app.add_subcommand("antenna", "the GPS antenna's lever arm from a drive with turns (GPS_VEL + IMU)"))
{
    sub_->add_option("log", log_, "LCM log with gps_velocity_t and imu_t")->required()->check(CLI::ExistingFile);
    sub_->add_option("--pose-config", pose_config_,
                     "ugv-pose's config: its gps_antenna_m is reported as configured and gives the height, which "
                     "level driving cannot (default: [0, 0, 0])")
        ->check(CLI::ExistingFile);
    sub_->add_option("--gps-channel", gps_channel_, "gps_velocity_t channel");
    sub_->add_option("--imu-channel", imu_channel_, "imu_t channel");
    sub_->add_option("--min-speed", fit_.min_speed_mps, "GPS velocities slower than this are left out (m/s)")
        ->check(CLI::Range(0.1, 20.0));
    sub_->add_flag("--json", json_, "one JSON line instead of the text and the gps_antenna_m line");
}

int AntennaCommand::run() const
{
    std::vector<double> configured;
    try {
        runtime::Config cfg = pose_config_.empty() ? runtime::Config::empty() : runtime::Config::load(pose_config_);
        configured = cfg.get_doubles("gps_antenna_m", {0.0, 0.0, 0.0}, 3, -20.0, 20.0);
    } catch (const runtime::ConfigError& e) {
        std::fprintf(stderr, "ugv-calibrate: %s\n", e.what());
        return 2;
    }

    std::vector<calibrate::ImuRateSample> imu;
    std::vector<calibrate::GpsVelocitySample> gps;
    uint64_t malformed = 0;
    int64_t origin = 0;
    auto seconds = [&](int64_t utime) {
        if (origin == 0) origin = utime;
        return static_cast<double>(utime - origin) * 1e-6;
    };
    imu_t m{};
    gps_velocity_t v{};
    const bool read = for_each_event(log_, [&](const lcm::LogEvent& ev) {
        const auto n = static_cast<std::size_t>(ev.datalen);
        if (ev.channel == imu_channel_) {
            if (!bus::decode_checked(ev.data, n, m)) {
                ++malformed;
                return;
            }
            const int32_t need = static_cast<int32_t>(imu_t::VALID_ANGULAR_RATE) | static_cast<int32_t>(imu_t::VALID_ACCELERATION);
            if ((m.valid & need) == need)
                imu.push_back({seconds(m.utime), m.angular_rate[2], m.acceleration[0], m.acceleration[1]});
        } else if (ev.channel == gps_channel_) {
            if (!bus::decode_checked(ev.data, n, v)) {
                ++malformed;
                return;
            }
            if (std::isfinite(v.horizontal_speed) && std::isfinite(v.track))
                gps.push_back({seconds(v.utime), v.horizontal_speed, geometry::enu_yaw_from_track(v.track)});
        }
    });
    if (!read) {
        std::fprintf(stderr, "ugv-calibrate: %s: not an LCM log\n", log_.c_str());
        return 2;
    }
    if (malformed > 0)
        std::fprintf(stderr, "ugv-calibrate: %llu malformed message(s) skipped\n", static_cast<unsigned long long>(malformed));
    if (imu.size() < 2 || gps.empty()) {
        std::fprintf(stderr, "ugv-calibrate: %s: no %s on %s with %s on %s: record both while driving with turns\n",
                     log_.c_str(), "gps_velocity_t", gps_channel_.c_str(), "imu_t", imu_channel_.c_str());
        return 2;
    }
    // The log's order is arrival order; the fit wants measurement time.
    auto by_time = [](const auto& a, const auto& b) { return a.t_s < b.t_s; };
    std::stable_sort(imu.begin(), imu.end(), by_time);
    std::stable_sort(gps.begin(), gps.end(), by_time);

    const calibrate::AntennaFitResult r =
        calibrate::fit_antenna(calibrate::antenna_samples(imu, gps), configured[0], configured[1], fit_);
    if (!r.failure.empty()) {
        std::fprintf(stderr, "ugv-calibrate: %s: %s\n", log_.c_str(), r.failure.c_str());
        return 2;
    }
    calibrate::ParamEstimate z;
    z.initial = z.value = configured[2];
    z.sigma = INFINITY;
    auto why_not = [&](const calibrate::ParamEstimate& e, const char* help) {
        char buf[200];
        std::snprintf(buf, sizeof buf, "its sigma %.3f m is above %.3f m (%s)", e.sigma, fit_.max_sigma_m, help);
        return std::string(buf);
    };
    if (json_) {
        std::printf("{\"samples\": %zu, \"turning_samples\": %zu, \"turn_deg\": %.1f, \"max_yaw_rate_radps\": %.4f, "
                    "\"lateral_rms_mps\": %.4f, \"accel_rms_mps2\": %.4f, %s, %s, %s}\n",
                    r.samples, r.turning_samples, r.turn_deg, r.max_yaw_rate_radps, r.lateral_rms_mps, r.accel_rms_mps2,
                    json_param("x_m", r.x, 1.0).c_str(), json_param("y_m", r.y, 1.0).c_str(),
                    json_param("z_m", z, 1.0).c_str());
        return 0;
    }
    std::printf("%zu GPS velocities while moving, %zu of them turning (up to %.3f rad/s), %.0f deg turned\n", r.samples,
                r.turning_samples, r.max_yaw_rate_radps, r.turn_deg);
    std::printf("residual RMS: sideways velocity %.3f m/s, centripetal acceleration %.3f m/s^2\n", r.lateral_rms_mps,
                r.accel_rms_mps2);
    print_param("x", r.x, 1.0, "m", why_not(r.x, "turn more, or faster"));
    print_param("y", r.y, 1.0, "m", why_not(r.y, "its signal is the yaw rate squared: tighter turns, level ground"));
    print_param("z", z, 1.0, "m", "level driving does not move with it");
    std::printf("\n# ugv-pose's lever arm, estimated by ugv-calibrate antenna from %s\n", log_.c_str());
    std::printf("gps_antenna_m = [%.4f, %.4f, %.4f]\n", r.x.value, r.y.value, z.value);
    return 0;
}

}  // namespace ugv::calibrate_tool
