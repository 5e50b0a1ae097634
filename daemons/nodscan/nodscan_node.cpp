#include "nodscan_node.hpp"

#include <algorithm>
#include <cmath>

#include <spdlog/spdlog.h>

#include "nodscan_messages.hpp"
#include "ugv/bus/typed.hpp"
#include "ugv/daemon/input_stamps.hpp"
#include "ugv/io/clock.hpp"
#include "ugv/runtime/counters.hpp"

namespace ugv::nodscan_daemon {
namespace {

// An LMS 2xx sweeps 180 degrees in 13-27 ms; a scan said to last longer is a bad time field
// (and a huge one would take its last beam's time past int64).
constexpr double kMaxScanSpanS = 1.0;

bool timing_ok(const laser_scan_t& s)
{
    const nodscan::ScanView v = to_scan_view(s);
    return v.sweeps >= 1 && std::isfinite(s.time_increment) && s.time_increment >= 0.0 &&
           static_cast<double>(s.time_increment) * std::max(0, s.nranges - 1) <= kMaxScanSpanS &&
           v.span_s() <= kMaxScanSpanS;
}

}  // namespace

NodscanNode::NodscanNode(const NodscanConfig& config, Publish publish)
    : config_(config), publish_(std::move(publish)), servo_(config.servo_history_us), assembler_(config.assembler)
{
}

void NodscanNode::on_servo(const servo_state_t& msg)
{
    if (!servo_.add({msg.utime, msg.angle})) {
        ++counters_.servo_rejected;
        return;
    }
    newest_message_utime_ = std::max(newest_message_utime_, msg.utime);
    process_ready();
}

void NodscanNode::on_scan(const laser_scan_t& msg)
{
    if (!config_.sensor_id.empty() && msg.sensor_id != config_.sensor_id) {
        ++counters_.scans_other_sensor;
        return;
    }
    ++counters_.scans_in;
    if (!timing_ok(msg)) {
        ++counters_.scans_bad_timing;
        return;
    }
    pending_.push_back(msg);
    newest_message_utime_ = std::max(newest_message_utime_, msg.utime);
    while (pending_.size() > config_.max_pending_scans) {
        ++counters_.scans_overflow;
        assemble(pending_.front());  // the oldest has waited longest: use what there is
        pending_.pop_front();
    }
    process_ready();
}

void NodscanNode::process_ready()
{
    while (!pending_.empty()) {
        const laser_scan_t& scan = pending_.front();
        const int64_t last_beam = nodscan::ScanAssembler::last_beam_utime(to_scan_view(scan));
        const bool bracketed = servo_.newest_utime() >= last_beam;
        const bool waited_enough = newest_message_utime_ > last_beam + config_.max_wait_us;
        if (!bracketed && !waited_enough) break;
        assemble(scan);
        pending_.pop_front();
    }
}

void NodscanNode::flush_older_than(int64_t message_utime)
{
    while (!pending_.empty() &&
           nodscan::ScanAssembler::last_beam_utime(to_scan_view(pending_.front())) < message_utime) {
        assemble(pending_.front());
        pending_.pop_front();
    }
}

void NodscanNode::flush_all()
{
    while (!pending_.empty()) {
        assemble(pending_.front());
        pending_.pop_front();
    }
}

void NodscanNode::assemble(const laser_scan_t& scan)
{
    const auto st = assembler_.assemble(to_scan_view(scan), servo_, cloud_);
    counters_.dropped_invalid += st.dropped_invalid;
    counters_.dropped_no_angle += st.dropped_no_angle;
    if (st.points == 0 && st.dropped_no_angle > 0) {
        ++counters_.scans_without_servo;
        return;
    }
    ++counters_.scans_out;
    counters_.points_out += st.points;
    publish_(to_message(cloud_, scan.sensor_id, seq_++));
}

int run(daemon::Daemon& d, const NodscanConfig& config)
{
    // Flowing: POINTS published (one cloud per scan that had servo angles).
    d.declare_output(config.channel, 2'000'000);
    bool any_published = false;
    // While every message of one input is refused: DEGRADED, saying which (no POINTS can
    // follow); RUNNING again once one is taken and POINTS flow. A servo sample older than the
    // history is of no use, nor a scan whose angles are gone.
    daemon::InputStamps stamps(d, {.max_ahead_us = config.max_stamp_ahead_us, .max_age_us = config.servo_history_us, .skew = config.stamp_skew},
                               [&] {
                                   if (any_published) d.ready();
                               });
    const int servo_input = stamps.add_input(config.servo_channel);
    const int scan_input = stamps.add_input(config.scan_channel);
    NodscanNode node(config, [&d, &config, &stamps, &any_published](const point_cloud_t& msg) {
        if (!bus::publish(d.out(), config.channel, msg)) return;
        d.mark_output();
        if (!any_published && !stamps.refusing()) d.ready();
        any_published = true;
    });
    const auto sync_counters = [&] { runtime::set_all(d.counters(), node.counters()); };
    sync_counters();  // every counter is listed from the first status message on
    bus::subscribe<servo_state_t>(d.bus(), config.servo_channel,
                                  [&](const std::string&, const servo_state_t& m, int64_t) {
                                      if (!stamps.accept(servo_input, m.utime)) return;
                                      node.on_servo(m);
                                      sync_counters();
                                  });
    bus::subscribe<laser_scan_t>(d.bus(), config.scan_channel, [&](const std::string&, const laser_scan_t& m, int64_t) {
        if (!stamps.accept(scan_input, m.utime)) return;
        node.on_scan(m);
        sync_counters();
    });
    if (!d.replaying()) {
        // Live: a scan whose servo stream stalled is not held longer than max_wait of wall time.
        d.add_timer(config.max_wait_us > 0 ? config.max_wait_us : 10'000, [&] {
            node.flush_older_than(io::now_utime() - config.max_wait_us);
            sync_counters();
        });
    }
    spdlog::info("assembling {} + {} -> {}", config.scan_channel, config.servo_channel, config.channel);
    return d.run();
}

}  // namespace ugv::nodscan_daemon
