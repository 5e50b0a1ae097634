#include "imu_command.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "log_events.hpp"
#include "report.hpp"
#include "ugv/bus/typed.hpp"
#include "ugv/imu_t.hpp"
#include "ugv/runtime/config.hpp"

namespace ugv::calibrate_tool {

namespace {
constexpr double kDeg = std::numbers::pi / 180.0;
}

ImuCommand::ImuCommand(CLI::App& app)
    : sub_(app.add_subcommand("imu", "the IMU's mounting from standing still and straight acceleration (IMU)"))
{
    sub_->add_option("log", log_, "LCM log with imu_t")->required()->check(CLI::ExistingFile);
    sub_->add_option("--mount-config", mount_config_,
                     "ugv-imu's config of the recording: its mount_rpy_deg turned the samples (default: [0, 0, 0])")
        ->check(CLI::ExistingFile);
    sub_->add_option("--channel", channel_, "imu_t channel");
    sub_->add_option("--min-still", fit_.min_still_s, "still time needed (s)")->check(CLI::Range(1.0, 600.0));
    sub_->add_flag("--json", json_, "one JSON line instead of the text and the mount_rpy_deg line");
}

int ImuCommand::run() const
{
    Eigen::Vector3d configured;
    try {
        runtime::Config cfg = mount_config_.empty() ? runtime::Config::empty() : runtime::Config::load(mount_config_);
        const std::vector<double> rpy = cfg.get_doubles("mount_rpy_deg", {0.0, 0.0, 0.0}, 3, -180.0, 180.0);
        configured = Eigen::Vector3d(rpy[0], rpy[1], rpy[2]) * kDeg;
    } catch (const runtime::ConfigError& e) {
        std::fprintf(stderr, "ugv-calibrate: %s\n", e.what());
        return 2;
    }

    std::vector<calibrate::ImuMountSample> samples;
    uint64_t malformed = 0;
    int64_t origin = 0;
    imu_t m{};
    const bool read = for_each_event(log_, [&](const lcm::LogEvent& ev) {
        if (ev.channel != channel_) return;
        if (!bus::decode_checked(ev.data, static_cast<std::size_t>(ev.datalen), m)) {
            ++malformed;
            return;
        }
        const int32_t need = static_cast<int32_t>(imu_t::VALID_ANGULAR_RATE) | static_cast<int32_t>(imu_t::VALID_ACCELERATION);
        if ((m.valid & need) != need) return;
        if (origin == 0) origin = m.utime;
        calibrate::ImuMountSample s;
        s.t_s = static_cast<double>(m.utime - origin) * 1e-6;
        s.accel_mps2 = {m.acceleration[0], m.acceleration[1], m.acceleration[2]};
        s.rate_radps = {m.angular_rate[0], m.angular_rate[1], m.angular_rate[2]};
        if (m.valid & imu_t::VALID_ORIENTATION) {
            const Eigen::Quaterniond q(m.orientation[0], m.orientation[1], m.orientation[2], m.orientation[3]);
            s.up = q.normalized().conjugate() * Eigen::Vector3d::UnitZ();
            s.has_up = true;
        }
        samples.push_back(s);
    });
    if (!read) {
        std::fprintf(stderr, "ugv-calibrate: %s: not an LCM log\n", log_.c_str());
        return 2;
    }
    if (malformed > 0)
        std::fprintf(stderr, "ugv-calibrate: %llu malformed message(s) skipped\n", static_cast<unsigned long long>(malformed));
    if (samples.empty()) {
        std::fprintf(stderr, "ugv-calibrate: %s: no %s with rates and accelerations on %s: record it standing, then "
                     "driving straight\n", log_.c_str(), "imu_t", channel_.c_str());
        return 2;
    }
    std::stable_sort(samples.begin(), samples.end(), [](const auto& a, const auto& b) { return a.t_s < b.t_s; });

    const calibrate::ImuMountFitResult r = calibrate::fit_imu_mount(samples, configured, fit_);
    if (!r.failure.empty()) {
        std::fprintf(stderr, "ugv-calibrate: %s: %s\n", log_.c_str(), r.failure.c_str());
        return 2;
    }
    const char* names[] = {"roll", "pitch", "yaw"};
    if (json_) {
        std::printf("{\"samples\": %zu, \"span_s\": %.1f, \"still_s\": %.1f, \"still_periods\": %d, \"gravity_mps2\": %.4f, "
                    "\"accel_samples\": %zu, \"accel_events\": %d, \"max_accel_mps2\": %.3f, "
                    "\"residual_rpy_deg\": [%.4f, %.4f, %.4f]",
                    samples.size(), r.span_s, r.still_s, r.still_periods, r.gravity_mps2, r.accel_samples,
                    r.accel_events, r.max_accel_mps2, r.residual_rpy_rad.x() / kDeg, r.residual_rpy_rad.y() / kDeg,
                    r.residual_rpy_rad.z() / kDeg);
        for (int k = 0; k < calibrate::kImuAngles; ++k)
            std::printf(", %s", json_param(std::string(names[k]) + "_deg", r.params[static_cast<std::size_t>(k)], 1.0 / kDeg).c_str());
        std::printf("}\n");
        return 0;
    }
    std::printf("%zu IMU samples over %.1f s; still %.1f s in %d period(s) (gravity %.4f m/s^2); straight "
                "acceleration: %zu samples in %d event(s), up to %.2f m/s^2\n",
                samples.size(), r.span_s, r.still_s, r.still_periods, r.gravity_mps2, r.accel_samples, r.accel_events,
                r.max_accel_mps2);
    std::printf("the configured mounting is off by roll %.3f, pitch %.3f, yaw %.3f deg\n", r.residual_rpy_rad.x() / kDeg,
                r.residual_rpy_rad.y() / kDeg, r.residual_rpy_rad.z() / kDeg);
    for (int k = 0; k < calibrate::kImuAngles; ++k) {
        const calibrate::ParamEstimate& e = r.params[static_cast<std::size_t>(k)];
        char why[200];
        if (k == calibrate::kImuYaw && r.accel_samples < fit_.min_accel_samples)
            std::snprintf(why, sizeof why, "%zu straight acceleration samples, at least %zu (speed up and brake "
                          "harder or more often)", r.accel_samples, fit_.min_accel_samples);
        else
            std::snprintf(why, sizeof why, "its sigma %.3f deg is above %.3f deg", e.sigma / kDeg, fit_.max_sigma_deg);
        print_param(names[k], e, 1.0 / kDeg, "deg", why);
    }
    std::printf("roll and pitch take the body as level while it stood: a ground slope of s deg is an error of up to "
                "s deg (stand facing both ways on the same spot to average it out)\n");
    std::printf("\n# ugv-imu's mounting, estimated by ugv-calibrate imu from %s\n", log_.c_str());
    std::printf("mount_rpy_deg = [%.4f, %.4f, %.4f]\n", r.params[0].value / kDeg, r.params[1].value / kDeg,
                r.params[2].value / kDeg);
    return 0;
}

}  // namespace ugv::calibrate_tool
