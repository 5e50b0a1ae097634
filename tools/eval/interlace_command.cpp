#include "interlace_command.hpp"

#include <lcm/lcm-cpp.hpp>

#include <cmath>
#include <cstdio>

#include "ugv/bus/typed.hpp"
#include "ugv/laser_scan_t.hpp"
#include "ugv/nodscan/interlace_order.hpp"
#include "ugv/servo_state_t.hpp"

namespace ugv::eval {

InterlaceCommand::InterlaceCommand(CLI::App& app)
    : sub_(app.add_subcommand("interlace", "which sweep order of an interlacing laser fits a nodding log"))
{
    sub_->add_option("log", log_, "LCM log with laser_scan_t and servo_state_t")->required()->check(CLI::ExistingFile);
    sub_->add_option("--scan-channel", scan_channel_, "laser_scan_t channel");
    sub_->add_option("--servo-channel", servo_channel_, "servo_state_t channel");
    sub_->add_option("--sensor-id", sensor_id_, "only scans of this sensor_id (default: any)");
    sub_->add_option("--max-range", max_range_m_, "beams further than this are not scored (m)")
        ->check(CLI::Range(1.0, 1000.0));
    sub_->add_option("--min-margin", min_margin_, "the runner-up's zig-zag over the best's needed to name an order")
        ->check(CLI::Range(1.0, 100.0));
    sub_->add_flag("--json", json_, "one JSON line per candidate, then a summary line");
}

int InterlaceCommand::run() const
{
    lcm::LogFile log(log_, "r");
    if (!log.good()) {
        std::fprintf(stderr, "ugv-eval: %s: not an LCM log\n", log_.c_str());
        return 2;
    }
    nodscan::InterlaceConfig cfg;
    cfg.max_range_m = max_range_m_;
    nodscan::InterlaceDetector detector(cfg);
    laser_scan_t scan{};
    servo_state_t servo{};
    uint64_t malformed = 0;
    while (const lcm::LogEvent* ev = log.readNextEvent()) {
        const auto n = static_cast<std::size_t>(ev->datalen);
        if (ev->channel == servo_channel_) {
            if (bus::decode_checked(ev->data, n, servo))
                detector.add_servo({servo.utime, servo.angle});
            else
                ++malformed;
        } else if (ev->channel == scan_channel_) {
            if (!bus::decode_checked(ev->data, n, scan)) {
                ++malformed;
                continue;
            }
            if (!sensor_id_.empty() && scan.sensor_id != sensor_id_) continue;
            const nodscan::ScanView v = nodscan::scan_view_of(scan);
            if (v.sweeps < 1) {
                ++malformed;
                continue;
            }
            detector.add_scan(v);
        }
    }
    if (malformed > 0) std::fprintf(stderr, "ugv-eval: %llu malformed message(s) skipped\n", static_cast<unsigned long long>(malformed));
    const nodscan::InterlaceResult r = detector.finish();
    const bool clear = r.best >= 0 && (r.runner_up < 0 || r.margin() >= min_margin_);
    const std::string fits = clear ? r.candidates[static_cast<std::size_t>(r.best)].name : "";
    // Scans whose own timing beats every interlaced order (a linear device, or a log of one).
    const double own = r.candidates[0].zigzag_rms_m;
    const bool own_fits = r.best >= 0 && own * min_margin_ <= r.candidates[static_cast<std::size_t>(r.best)].zigzag_rms_m;
    if (json_) {
        for (const nodscan::OrderScore& s : r.candidates)
            std::printf("{\"candidate\": \"%s\", \"zigzag_rms_m\": %.5f, \"triples\": %llu}\n", s.name.c_str(),
                        std::isfinite(s.zigzag_rms_m) ? s.zigzag_rms_m : -1.0, static_cast<unsigned long long>(s.triples));
        std::printf("{\"summary\": true, \"fits\": \"%s\", \"margin\": %.3f, \"scans\": %llu, \"scans_skipped\": %llu}\n",
                    own_fits ? "as published" : clear ? fits.c_str() : "unknown", r.margin(), static_cast<unsigned long long>(r.scans),
                    static_cast<unsigned long long>(r.scans_skipped));
    } else {
        std::printf("%-14s %16s %10s\n", "timing", "zig-zag RMS (m)", "triples");
        for (const nodscan::OrderScore& s : r.candidates)
            std::printf("%-14s %16.5f %10llu\n", s.name.c_str(), s.zigzag_rms_m, static_cast<unsigned long long>(s.triples));
        if (own_fits)
            std::printf("the scans' own timing fits better than any interlaced order (%.5f m against %.5f m): "
                        "these scans were not measured in interlaced sweeps\n",
                        own, r.candidates[static_cast<std::size_t>(r.best)].zigzag_rms_m);
        else if (clear)
            std::printf("sweep_order = \"%s\" fits (%llu scans; the next best has %.2fx its zig-zag)\n", fits.c_str(),
                        static_cast<unsigned long long>(r.scans), r.margin());
        else
            std::printf("cannot tell the order from this log (%llu scans scored; best two within %.2fx): record "
                        "a nodding scan of smooth ground\n",
                        static_cast<unsigned long long>(r.scans), min_margin_);
    }
    return clear || own_fits ? 0 : 1;
}

}  // namespace ugv::eval
