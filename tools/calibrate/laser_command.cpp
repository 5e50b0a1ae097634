#include "laser_command.hpp"

#include <lcm/lcm-cpp.hpp>

#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <vector>

#include "ugv/bus/typed.hpp"
#include "ugv/laser_scan_t.hpp"
#include "ugv/nodscan/mount_config.hpp"
#include "ugv/nodscan/scan_assembler.hpp"
#include "ugv/nodscan/servo_history.hpp"
#include "ugv/runtime/config.hpp"
#include "ugv/servo_state_t.hpp"

namespace ugv::calibrate_tool {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// An angle (rad) or a height (m) as printed: degrees or metres.
double shown(int k, double v) { return k == calibrate::kHeight ? v : v / kDeg; }

std::string triple(const Eigen::Vector3d& v, double scale, const char* format)
{
    char buf[160];
    std::snprintf(buf, sizeof buf, format, v.x() * scale, v.y() * scale, v.z() * scale);
    return buf;
}

}  // namespace

LaserCommand::LaserCommand(CLI::App& app)
    : sub_(app.add_subcommand("laser", "the nodding laser's mount from a log of flat ground (LMS_SCAN + SERVO_STATE)"))
{
    sub_->add_option("log", log_, "LCM log with laser_scan_t and servo_state_t")->required()->check(CLI::ExistingFile);
    sub_->add_option("--mount-config", mount_config_,
                     "ugv-nodscan's config: its [mount] is where the fit starts (default: ugv-nodscan's defaults)")
        ->check(CLI::ExistingFile);
    sub_->add_option("--scan-channel", scan_channel_, "laser_scan_t channel");
    sub_->add_option("--servo-channel", servo_channel_, "servo_state_t channel");
    sub_->add_option("--sensor-id", sensor_id_, "only scans of this sensor_id (default: any)");
    sub_->add_option("--min-range", fit_.min_range_m, "beams nearer than this are left out (m)")->check(CLI::Range(0.5, 100.0));
    sub_->add_option("--max-range", fit_.max_range_m, "beams further than this are left out (m)")->check(CLI::Range(1.0, 100.0));
    sub_->add_option("--max-beams", max_beams_, "beams used at most (scans taken evenly through the log)")
        ->check(CLI::Range(10000, 10000000));
    sub_->add_flag("--json", json_, "one JSON line instead of the text and the [mount] table");
}

int LaserCommand::run() const
{
    if (!(fit_.min_range_m < fit_.max_range_m)) {
        std::fprintf(stderr, "ugv-calibrate: --min-range must be below --max-range\n");
        return 2;
    }
    nodscan::MountGeometry initial;
    try {
        runtime::Config cfg = mount_config_.empty() ? runtime::Config::empty() : runtime::Config::load(mount_config_);
        runtime::Config m = cfg.section("mount");
        initial = nodscan::read_mount(m);
    } catch (const runtime::ConfigError& e) {
        std::fprintf(stderr, "ugv-calibrate: %s\n", e.what());
        return 2;
    }

    // First pass: every tilt sample, and where the scans lie in time.
    nodscan::ServoHistory tilts(std::numeric_limits<int64_t>::max() / 4);
    int64_t first_scan = std::numeric_limits<int64_t>::max(), last_scan = std::numeric_limits<int64_t>::min();
    std::size_t scans = 0, beams_in_scans = 0;
    uint64_t malformed = 0;
    laser_scan_t scan{};
    servo_state_t servo{};
    auto read = [&](auto&& on_scan) {
        lcm::LogFile log(log_, "r");
        if (!log.good()) return false;
        while (const lcm::LogEvent* ev = log.readNextEvent()) {
            const auto n = static_cast<std::size_t>(ev->datalen);
            if (ev->channel == servo_channel_) {
                if (!bus::decode_checked(ev->data, n, servo)) ++malformed;
                else on_scan(nullptr);
            } else if (ev->channel == scan_channel_) {
                if (!bus::decode_checked(ev->data, n, scan)) {
                    ++malformed;
                    continue;
                }
                if (!sensor_id_.empty() && scan.sensor_id != sensor_id_) continue;
                on_scan(&scan);
            }
        }
        return true;
    };
    if (!read([&](const laser_scan_t* s) {
            if (s == nullptr) {
                tilts.add({servo.utime, servo.angle});
                return;
            }
            ++scans;
            beams_in_scans += static_cast<std::size_t>(std::max(0, s->nranges));
            first_scan = std::min(first_scan, s->utime);
            last_scan = std::max(last_scan, s->utime);
        })) {
        std::fprintf(stderr, "ugv-calibrate: %s: not an LCM log\n", log_.c_str());
        return 2;
    }
    if (scans == 0 || tilts.empty()) {
        std::fprintf(stderr, "ugv-calibrate: %s: no %s on %s with %s on %s: record both while nodding\n", log_.c_str(),
                     "laser_scan_t", scan_channel_.c_str(), "servo_state_t", servo_channel_.c_str());
        return 2;
    }

    // Second pass: each beam with the tilt at its own time, every k-th scan.
    const std::size_t every = std::max<std::size_t>(1, (beams_in_scans + max_beams_ - 1) / max_beams_);
    const double block_us = std::max(1.0, static_cast<double>(last_scan - first_scan + 1) / blocks_);
    std::vector<calibrate::LaserBeam> beams;
    std::size_t scan_index = 0, no_tilt = 0;
    read([&](const laser_scan_t* s) {
        if (s == nullptr || scan_index++ % every != 0) return;
        const nodscan::ScanView v = nodscan::scan_view_of(*s);
        if (v.sweeps < 1) {
            ++malformed;
            return;
        }
        const auto block = static_cast<int32_t>(static_cast<double>(s->utime - first_scan) / block_us);
        for (std::size_t i = 0; i < v.n; ++i) {
            const float r = v.ranges[i];
            if (!(r > 0) || (v.range_max > 0 && r > v.range_max)) continue;
            const auto at = s->utime + static_cast<int64_t>(std::llround(v.beam_offset_s(i) * 1e6));
            const std::optional<double> tilt = tilts.angle_at(at);
            if (!tilt) {
                ++no_tilt;
                continue;
            }
            beams.push_back({r, static_cast<float>(v.angle_min + v.angle_increment * static_cast<double>(i)),
                             static_cast<float>(*tilt), block});
        }
    });
    if (malformed > 0)
        std::fprintf(stderr, "ugv-calibrate: %llu malformed message(s) skipped\n", static_cast<unsigned long long>(malformed));

    const calibrate::LaserFitResult r = calibrate::fit_laser_mount(beams, initial, fit_);
    if (!r.failure.empty()) {
        std::fprintf(stderr, "ugv-calibrate: %s: %s\n", log_.c_str(), r.failure.c_str());
        return 2;
    }
    auto why_not = [&](int k) -> std::string {
        if (k == calibrate::kYaw) return "flat ground does not move with it (needs vertical structure)";
        char buf[120];
        std::snprintf(buf, sizeof buf, "its sigma %.4f is above %.4f", shown(k, r.params[static_cast<std::size_t>(k)].sigma),
                      shown(k, k == calibrate::kHeight ? fit_.max_sigma_height_m : fit_.max_sigma_angle_deg * kDeg));
        return buf;
    };
    if (json_) {
        std::printf("{\"scans\": %zu, \"scans_used\": %zu, \"beams\": %zu, \"ground_beams\": %zu, \"no_tilt\": %zu, "
                    "\"tilt_span_deg\": %.2f, \"gate_m\": %.4f, \"rms_before_m\": %.4f, \"rms_after_m\": %.4f, "
                    "\"blocks\": %d",
                    scans, (scans + every - 1) / every, r.beams, r.ground_beams, no_tilt, r.tilt_span_deg, r.gate_m,
                    r.rms_before_m, r.rms_after_m, r.blocks);
        for (int k = 0; k < calibrate::kLaserParams; ++k) {
            const calibrate::ParamEstimate& e = r.params[static_cast<std::size_t>(k)];
            char sigma[32] = "null";
            if (std::isfinite(e.sigma)) std::snprintf(sigma, sizeof sigma, "%.5f", shown(k, e.sigma));
            std::printf(", \"%s_%s\": {\"value\": %.5f, \"sigma\": %s, \"initial\": %.5f, \"determined\": %s}",
                        calibrate::laser_param_name(static_cast<calibrate::LaserParam>(k)), k == calibrate::kHeight ? "m" : "deg",
                        shown(k, e.value), sigma, shown(k, e.initial), e.determined ? "true" : "false");
        }
        std::printf("}\n");
        return 0;
    }
    std::printf("%zu scans (%zu used), %zu beams between %.1f and %.1f m, tilt span %.1f deg; %zu on the ground "
                "(gate %.3f m)\n",
                scans, (scans + every - 1) / every, r.beams, fit_.min_range_m, fit_.max_range_m, r.tilt_span_deg,
                r.ground_beams, r.gate_m);
    std::printf("ground height RMS: %.3f m with the configured mount, %.3f m with the estimate\n", r.rms_before_m,
                r.rms_after_m);
    for (int k = 0; k < calibrate::kLaserParams; ++k) {
        const calibrate::ParamEstimate& e = r.params[static_cast<std::size_t>(k)];
        const char* name = calibrate::laser_param_name(static_cast<calibrate::LaserParam>(k));
        const char* unit = k == calibrate::kHeight ? "m  " : "deg";
        if (e.determined)
            std::printf("  %-7s %9.4f %s +- %.4f  (configured %.4f)%s\n", name, shown(k, e.value), unit, shown(k, e.sigma),
                        shown(k, e.initial),
                        k == calibrate::kPitch ? "; the servo's tilt zero and this pitch are one angle" : "");
        else
            std::printf("  %-7s not determined: %s; the configured %.4f %s is kept\n", name, why_not(k).c_str(),
                        shown(k, e.initial), unit);
    }
    std::printf("\n# ugv-nodscan's [mount], estimated by ugv-calibrate laser from %s\n[mount]\n", log_.c_str());
    std::printf("tilt_axis_xyz_m = %s\n", triple(r.mount.axis_xyz_m, 1.0, "[%.4f, %.4f, %.4f]").c_str());
    std::printf("tilt_axis_rpy_deg = %s\n", triple(r.mount.axis_rpy_rad, 1.0 / kDeg, "[%.4f, %.4f, %.4f]").c_str());
    std::printf("laser_xyz_m = %s\n", triple(r.mount.laser_xyz_m, 1.0, "[%.4f, %.4f, %.4f]").c_str());
    std::printf("laser_rpy_deg = %s\n", triple(r.mount.laser_rpy_rad, 1.0 / kDeg, "[%.4f, %.4f, %.4f]").c_str());
    return 0;
}

}  // namespace ugv::calibrate_tool
