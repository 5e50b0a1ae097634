#include "servo_node.hpp"

#include <cmath>
#include <cstdio>

#include <spdlog/spdlog.h>

#include "servo_messages.hpp"
#include "ugv/bus/typed.hpp"
#include "ugv/io/clock.hpp"
#include "ugv/runtime/counters.hpp"

namespace ugv::servo_daemon {
namespace {

// Receive errors in a row, without a frame between, after which the transport is reopened.
constexpr int kRxErrorsBeforeReopen = 50;
// TPDO periods per wake window: a few prompt TPDO1s per window, in case one is delayed.
constexpr int kWakeWindowPeriods = 5;

}  // namespace

ServoNode::ServoNode(daemon::Daemon& d, ServoConfig config)
    : d_(d),
      config_(std::move(config)),
      transport_(io::make_can_transport(config_.transport, config_.bitrate)),
      drive_(config_.drive),
      nod_(config_.nod),
      backoff_(100'000, 1'000'000)  // at most 1 s: a drive or adapter that is back runs within ~1.5 s
{
    sync_counters();  // every counter is listed from the first status message on
}

double ServoNode::now_s() const { return static_cast<double>(io::monotonic_us()) * 1e-6; }

void ServoNode::start()
{
    bus::subscribe<servo_command_t>(d_.bus(), config_.command_channel,
                                    [this](const std::string&, const servo_command_t& m, int64_t) { on_command(m); });
    d_.add_timer(config_.control_period_us, [this] { control_tick(); });
    // Flowing: SERVO_STATE while the drive is enabled and the nod profile runs.
    d_.declare_output("SERVO_STATE with the drive enabled and nodding", 500'000);
    open_transport();
}

void ServoNode::open_transport()
{
    if (!transport_->open()) {
        const int64_t wait = backoff_.next();
        retry_at_us_ = io::monotonic_us() + wait;
        log_.log(spdlog::level::warn, "open", transport_->last_error(), io::monotonic_us());
        d_.set_state(daemon::State::degraded, transport_->last_error());
        return;
    }
    transport_open_ = true;
    restart_scheduled_ = false;
    rx_errors_in_a_row_ = 0;
    if (ever_opened_) ++counters_.reconnects;
    ever_opened_ = true;
    watch_fd(true);
    spdlog::info("{} open at {} bit/s; configuring node {}", transport_->describe(), config_.bitrate,
                 int{config_.drive.node_id});
    drive_.start(io::monotonic_us());
    flush_outgoing();
}

void ServoNode::watch_fd(bool on)
{
    if (on && registered_fd_ < 0 && transport_open_) {
        registered_fd_ = transport_->fd();
        d_.add_fd(registered_fd_, [this] { drain_transport(true); });
    } else if (!on && registered_fd_ >= 0) {
        d_.remove_fd(registered_fd_);
        registered_fd_ = -1;
    }
}

bool ServoNode::want_frame_wakeups(int64_t now_us) const
{
    if (!drive_.operational()) return true;  // configuring, enabling: SDO answers at once
    if (transport_->stamps_arrival()) return false;
    if (config_.frame_wakeup_period_us == 0 || config_.drive.sync_period_us > 0) return true;
    const int64_t window_us = int64_t{kWakeWindowPeriods} * config_.drive.tpdo_period_ms * 1000;
    return now_us % config_.frame_wakeup_period_us < window_us;
}

void ServoNode::close_transport(const std::string& why)
{
    watch_fd(false);
    transport_->close();
    transport_open_ = false;
    was_operational_ = false;
    retry_at_us_ = io::monotonic_us() + backoff_.next();
    d_.set_state(daemon::State::degraded, why);
}

void ServoNode::reinitialise(const std::string& why)
{
    ++counters_.reinits;
    d_.notify_status("DEGRADED: " + why);
    was_operational_ = false;
    d_.set_state(daemon::State::degraded, why);
    // A missing mandatory object does not go away by retrying: said once, retried quietly.
    if (!drive_.mandatory_missing() || said_once_.insert(why).second)
        log_.log(spdlog::level::warn, "reinit", "re-initialising: " + why, io::monotonic_us());
    retry_at_us_ = io::monotonic_us() + backoff_.next();
}

void ServoNode::drain_transport(bool prompt)
{
    const bool read_late = !prompt && !transport_->stamps_arrival();
    for (int guard = 0; guard < 1000 && transport_open_; ++guard) {
        const io::CanReceive r = transport_->receive(0);
        if (r.status == io::CanReceive::Status::timeout) break;
        if (r.status == io::CanReceive::Status::frame) {
            rx_errors_in_a_row_ = 0;
            drive_.on_frame(r.frame, io::monotonic_us(), r.utime, read_late);
            continue;
        }
        if (r.status == io::CanReceive::Status::error && ++rx_errors_in_a_row_ < kRxErrorsBeforeReopen) {
            // A malformed slcan line (line noise, a byte lost) or one failed read: dropped.
            ++counters_.rx_errors;
            drive_.note_lost_frame();
            log_.log(spdlog::level::warn, "rx", "receive error: " + r.detail, io::monotonic_us());
            continue;
        }
        if (r.status == io::CanReceive::Status::bus_error) {
            // Bus-off or an adapter error: the controller needs an explicit restart.
            ++counters_.bus_errors;
            log_.log(spdlog::level::warn, "bus", "bus error: " + r.detail + "; restarting the CAN interface",
                     io::monotonic_us());
            close_transport("bus error: " + r.detail);
            break;
        }
        log_.log(spdlog::level::warn, "closed", "transport lost: " + r.detail, io::monotonic_us());
        close_transport("transport lost: " + r.detail);
        break;
    }
    flush_outgoing();
    publish_samples();
    log_events();
}

void ServoNode::control_tick()
{
    const int64_t now = io::monotonic_us();
    if (!transport_open_) {
        if (now >= retry_at_us_) open_transport();
        sync_counters();
        return;
    }
    // The bus between wake windows (and the slcan transport may hold decoded frames the fd
    // does not show).
    drain_transport(false);
    if (!transport_open_) return;
    drive_.tick(now);
    const auto phase = drive_.phase();
    if (phase == canopen::Drive::Phase::failed) {
        if (!restart_scheduled_) {
            // DEGRADED, and a restart after the back-off.
            reinitialise(drive_.heard_since_start()
                             ? drive_.failure()
                             : drive_.failure() + "; nothing received from the bus at " +
                                   std::to_string(config_.bitrate) + " bit/s: check the drive's power, node_id " +
                                   std::to_string(config_.drive.node_id) + " and that the bus runs at `bitrate`");
            restart_scheduled_ = true;
        } else if (now >= retry_at_us_) {
            spdlog::info("re-initialising node {}", int{config_.drive.node_id});
            restart_scheduled_ = false;
            drive_.start(now);
        }
    } else if (drive_.operational()) {
        const auto last = drive_.last_sample();
        const double angle = last ? last->angle_rad : 0.0;
        if (!was_operational_) {
            if (!nod_.started()) {
                if (auto why = nod_.apply(config_.default_profile, now_s(), angle)) spdlog::error("default profile: {}", *why);
            } else {
                nod_.resume(now_s(), angle);
            }
            backoff_.reset();
            was_operational_ = true;
            d_.ready();
            d_.notify_status("node " + std::to_string(config_.drive.node_id) + " operation enabled, profile " +
                             nodscan::to_string(nod_.kind()));
        }
        const auto out = nod_.update(now_s(), angle);
        drive_.command(out.angle_rad, out.speed_rad_s);
    } else if (was_operational_ && phase == canopen::Drive::Phase::enabling) {
        d_.set_state(daemon::State::degraded, "drive left operation enabled (fault)");
        was_operational_ = false;
    }
    flush_outgoing();
    publish_samples();
    log_events();
    sync_counters();
    watch_fd(transport_open_ && want_frame_wakeups(now));
}

void ServoNode::flush_outgoing()
{
    for (const auto& f : drive_.take_outgoing()) {
        if (!transport_open_) break;
        if (!transport_->send(f)) {
            ++counters_.tx_failures;  // e.g. ENOBUFS on a busy bus: the session's timeouts retry
            log_.log(spdlog::level::warn, "tx", "send failed: " + transport_->last_error(), io::monotonic_us());
        }
    }
}

void ServoNode::publish_samples()
{
    for (const auto& s : drive_.take_samples()) {
        bus::publish(d_.out(), config_.channel, to_message(s, nod_.kind(), drive_.last_emcy_code(), seq_++));
        ++counters_.samples;
        if (drive_.operational() && nod_.started()) d_.mark_output();
    }
}

void ServoNode::log_events()
{
    for (const auto& e : drive_.take_events()) {
        // The plan's degradations and a missing mandatory object: one line each, not one per
        // re-initialisation.
        const bool once = e.text.rfind("degraded: ", 0) == 0 || (drive_.mandatory_missing() && e.text == drive_.failure());
        if (once && !said_once_.insert(e.text).second) continue;
        const auto level = e.level == canopen::DriveEvent::Level::error     ? spdlog::level::err
                           : e.level == canopen::DriveEvent::Level::warning ? spdlog::level::warn
                                                                            : spdlog::level::info;
        log_.log(level, e.text.substr(0, 24), e.text, io::monotonic_us());
    }
}

void ServoNode::on_command(const servo_command_t& msg)
{
    const auto cmd = from_message(msg, config_.default_profile.scan_period_s);
    const auto last = drive_.last_sample();
    // One key per outcome, not per reason: a flood of commands writes a line per interval
    // with the count of the others, and the reasons (which quote values) never fill the map.
    if (auto why = nod_.apply(cmd, now_s(), last ? last->angle_rad : 0.0)) {
        ++counters_.commands_refused;
        log_.log(spdlog::level::warn, "command refused", "SERVO_COMMAND refused: " + *why, io::monotonic_us());
        return;
    }
    ++counters_.commands_accepted;
    log_.log(spdlog::level::info, "command accepted", std::string("SERVO_COMMAND accepted: profile ") + nodscan::to_string(cmd.kind),
             io::monotonic_us());
}

void ServoNode::sync_counters()
{
    runtime::set_all(d_.counters(), drive_.counters());
    runtime::set_all(d_.counters(), counters_);
}

void ServoNode::shutdown()
{
    if (!transport_open_) return;
    const int64_t start = io::monotonic_us();
    drive_.stop(start);
    flush_outgoing();
    const auto limit = static_cast<int64_t>(config_.shutdown_timeout_s * 1e6);
    while (drive_.phase() != canopen::Drive::Phase::stopped && io::monotonic_us() - start < limit) {
        const io::CanReceive r = transport_->receive(5);
        if (r.status == io::CanReceive::Status::frame) drive_.on_frame(r.frame, io::monotonic_us(), r.utime);
        else if (r.status != io::CanReceive::Status::timeout) break;
        drive_.tick(io::monotonic_us());
        flush_outgoing();
    }
    (void)drive_.take_samples();  // the bus is closed once Daemon::run() has returned
    log_events();
    if (drive_.phase() == canopen::Drive::Phase::stopped) spdlog::info("drive halted and disabled");
    else spdlog::warn("drive did not confirm halt and disable within {:.1f} s", config_.shutdown_timeout_s);
    transport_->close();
    transport_open_ = false;
}

int probe(const ServoConfig& config)
{
    const auto transport = io::make_can_transport(config.transport, config.bitrate);
    if (!transport->open()) {
        std::fprintf(stderr, "ugv-servo --probe: %s\n", transport->last_error().c_str());
        return 1;
    }
    canopen::Drive drive(config.drive);
    drive.start(io::monotonic_us(), /*probe_only=*/true);
    const int64_t deadline = io::monotonic_us() + 10'000'000;
    while (drive.phase() == canopen::Drive::Phase::configuring && io::monotonic_us() < deadline) {
        for (const auto& f : drive.take_outgoing()) transport->send(f);
        const io::CanReceive r = transport->receive(2);
        if (r.status == io::CanReceive::Status::frame) drive.on_frame(r.frame, io::monotonic_us(), r.utime);
        else if (r.status != io::CanReceive::Status::timeout && r.status != io::CanReceive::Status::error) break;
        drive.tick(io::monotonic_us());
    }
    transport->close();
    if (drive.phase() != canopen::Drive::Phase::probed) {
        std::fprintf(stderr, "ugv-servo --probe: no drive answered as node %d on %s at %d bit/s (%s)\n",
                     int{config.drive.node_id}, config.transport.c_str(), config.bitrate,
                     drive.failure().empty() ? "no answer" : drive.failure().c_str());
        return 1;
    }
    std::printf("node %d on %s at %d bit/s\n%s%s", int{config.drive.node_id}, config.transport.c_str(), config.bitrate,
                canopen::describe(drive.capabilities()).c_str(), canopen::describe(drive.plan()).c_str());
    return 0;
}

int run(daemon::Daemon& d, ServoConfig config)
{
    ServoNode node(d, std::move(config));
    node.start();
    const int rc = d.run();
    node.shutdown();  // halt, then disable
    return rc;
}

}  // namespace ugv::servo_daemon
