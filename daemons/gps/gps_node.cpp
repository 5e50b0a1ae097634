#include "gps_node.hpp"

#include <chrono>
#include <thread>
#include <vector>

#include <spdlog/spdlog.h>

#include "gps_messages.hpp"
#include "ugv/bus/typed.hpp"
#include "ugv/daemon/raw_bytes.hpp"
#include "ugv/io/clock.hpp"
#include "ugv/io/serial_port.hpp"
#include "ugv/novatel/session.hpp"
#include "ugv/runtime/backoff.hpp"
#include "ugv/runtime/counters.hpp"

namespace ugv::gps_daemon {
namespace {

constexpr int kPollMs = 50;
// Where a silent receiver is looked for (configure mode), the usual rates first: one left at
// another rate by a different host, or by a COM command of an earlier configuration.
const std::vector<int> kProbeBauds = {9600, 115200, 57600, 38400, 19200, 230400, 460800, 921600, 4800};

// Sleeps up to us, waking early when the daemon is asked to stop.
void sleep_unless_stopped(const daemon::Daemon& d, int64_t us)
{
    const int64_t end = io::monotonic_us() + us;
    while (!d.stop_requested() && io::monotonic_us() < end) {
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
}

// The daemon's own counters (the libraries' are listed by their structs).
const char* kNodeCounterNames[] = {
    "ignored_protocol", "superseded", "fixes_published", "velocities_published", "reconnects", "silences",
    "configure_failures", "open_failures", "clock_offset_us", "clock_offset_last_us", "clock_jumps", "time_status",
    "host_clock_offset_us", "host_clock_offset_valid",
};

}  // namespace

GpsNode::GpsNode(daemon::Daemon& daemon, GpsConfig config)
    : daemon_(daemon), config_(std::move(config)),
      interpreter_(novatel::InterpreterConfig{config_.leap_seconds, config_.output_latency_us, config_.baud,
                                              2'000'000})
{
    // Every counter is listed from the first status message on.
    for (const char* name : kNodeCounterNames) daemon_.counters()[name];
    update_counters(nullptr);
    // Flowing: fixes published, none missing for longer than the receiver's silence timeout.
    daemon_.declare_output("fixes on " + config_.channel_fix, config_.silence_timeout_us);
}

bool GpsNode::wanted(novatel::FrameKind kind) const
{
    using novatel::FrameKind;
    switch (config_.protocol) {
    case Protocol::nmea: return kind == FrameKind::nmea || kind == FrameKind::reply || kind == FrameKind::prompt;
    case Protocol::novatel: return kind != FrameKind::nmea;
    case Protocol::automatic: return true;
    }
    return true;
}

void GpsNode::on_message(const novatel::Decoded& m)
{
    if (!wanted(m.kind)) {
        ++ignored_;
        return;
    }
    const auto out = interpreter_.on_message(m.message, m.kind, m.arrival_utime, m.frame_bytes);
    auto& counters = daemon_.counters();
    if (out.fix) {
        const bool sent = bus::publish(daemon_.out(), config_.channel_fix, to_message(*out.fix, fix_seq_++));
        ++counters["fixes_published"];
        ++fixes_;
        if (sent) daemon_.mark_output();
        data_flowing_ = true;
    }
    if (out.velocity) {
        bus::publish(daemon_.out(), config_.channel_vel, to_message(*out.velocity, vel_seq_++));
        ++counters["velocities_published"];
    }
}

void GpsNode::publish_raw(const uint8_t* data, std::size_t n, int64_t utime)
{
    bus::publish(daemon_.out(), config_.channel_raw,
                 daemon::raw_bytes_message(config_.raw_device_name, false, data, n, utime, raw_seq_++));
}

void GpsNode::update_counters(const novatel::Session* session)
{
    auto& c = daemon_.counters();
    runtime::set_all(c, decoder_.splitter_counters());
    runtime::set_all(c, decoder_.counters());
    novatel::SessionCounters sessions = sessions_;
    if (session) sessions += session->counters();
    runtime::set_all(c, sessions);
    c["ignored_protocol"] = static_cast<int64_t>(ignored_);
    c["superseded"] = static_cast<int64_t>(interpreter_.superseded());
    const auto& clock = interpreter_.clock();
    if (clock.valid()) {
        c["clock_offset_us"] = clock.smoothed_us();
        c["clock_offset_last_us"] = clock.last_us();
        c["clock_jumps"] = static_cast<int64_t>(clock.jumps());
    }
    c["time_status"] = static_cast<int64_t>(interpreter_.last_time_status());
    // This host's clock against GPS time (docs/time.md): valid once the receiver's time is FINE.
    const auto& host = interpreter_.host_clock();
    c["host_clock_offset_valid"] = host.valid() ? 1 : 0;
    if (host.valid()) c["host_clock_offset_us"] = host.smoothed_us();
}

void GpsNode::run()
{
    auto& counters = daemon_.counters();
    runtime::Backoff backoff;
    bool ever_opened = false;
    const auto sink = [this](const novatel::Decoded& m) { on_message(m); };
    while (!daemon_.stop_requested()) {
        io::SerialPort port;
        if (!port.open(config_.device, config_.baud)) {
            ++counters["open_failures"];
            daemon_.set_state(daemon::State::degraded, port.last_error());
            sleep_unless_stopped(daemon_, backoff.next());
            continue;
        }
        if (ever_opened) {
            ++counters["reconnects"];
        }
        ever_opened = true;
        novatel::SessionConfig sc;
        sc.configure = config_.configure;
        sc.logs = config_.logs;
        sc.com_baud = config_.com_baud;
        sc.reply_timeout_ms = config_.reply_timeout_ms;
        sc.silence_timeout_us = config_.silence_timeout_us;
        sc.probe_bauds = kProbeBauds;
        novatel::Session session(port, decoder_, sc);
        if (config_.publish_raw) {
            session.set_raw_tap([this](const uint8_t* p, std::size_t n, int64_t t) { publish_raw(p, n, t); });
        }
        serve(port, session, backoff, sink);
        sessions_ += session.counters();
        update_counters(nullptr);
        if (daemon_.stop_requested()) {
            break;
        }
        // Only a device that is gone gets here: reopen it after the back-off.
        daemon_.set_state(daemon::State::degraded, config_.device + ": " + session.error());
        port.close();
        sleep_unless_stopped(daemon_, backoff.next());
    }
}

bool GpsNode::start_session(io::SerialPort& port, novatel::Session& session, const novatel::Decoder::Sink& sink)
{
    const uint64_t probed_before = session.counters().found_by_probing;
    const bool started = session.start(sink);
    if (session.counters().found_by_probing > probed_before) {
        spdlog::warn("{}: receiver answered at {} baud, not at the configured {}; set it back with COM", config_.device,
                     session.found_at_baud(), config_.com_baud > 0 ? config_.com_baud : config_.baud);
    }
    if (!started) {
        ++daemon_.counters()["configure_failures"];
        daemon_.set_state(daemon::State::degraded, "configure " + config_.device + ": " + session.error());
        return false;
    }
    spdlog::info("{}: session started ({}, {} baud)", config_.device, config_.configure ? "configured" : "passive",
                 port.baud());
    return true;
}

void GpsNode::serve(io::SerialPort& port, novatel::Session& session, runtime::Backoff& backoff,
                    const novatel::Decoder::Sink& sink)
{
    auto& counters = daemon_.counters();
    // Configure mode configures again, on this open port, while nothing comes (a receiver
    // that restarted has forgotten its logs); passive mode only listens.
    bool configured = start_session(port, session, sink);
    int64_t configure_at_us = configured ? 0 : io::monotonic_us() + backoff.next();
    bool silent = false;
    uint64_t fixes_seen = fixes_;
    while (!daemon_.stop_requested() && !session.stream_closed()) {
        if (!configured && io::monotonic_us() >= configure_at_us) {
            configured = start_session(port, session, sink);
            if (!configured) {
                configure_at_us = io::monotonic_us() + backoff.next();
            }
            continue;
        }
        const novatel::Session::Status status = session.poll(kPollMs, sink);
        update_counters(&session);
        if (status == novatel::Session::Status::closed || status == novatel::Session::Status::error) {
            return;
        }
        if (fixes_ != fixes_seen) {
            fixes_seen = fixes_;
            // Fixes again: RUNNING (the state follows the fixes' flow from here on).
            if (silent || daemon_.state() == daemon::State::degraded) {
                daemon_.set_state(daemon::State::running);
            }
            silent = false;
            backoff.reset();
        }
        if (status != novatel::Session::Status::silent) {
            continue;
        }
        if (!silent) {
            // DEGRADED, counted once per silence; the port stays open and is read on.
            silent = true;
            ++counters["silences"];
            daemon_.set_state(daemon::State::degraded, config_.device + ": " + session.error());
        }
        if (config_.configure && configured) {
            configured = false;
            configure_at_us = io::monotonic_us() + backoff.next();
        }
    }
}

int run(daemon::Daemon& d, const GpsConfig& config)
{
    GpsNode node(d, config);
    std::thread device;
    // The bus's publishing side exists once run() has started: start the device thread from
    // the main loop, which also sends READY=1 once fixes flow.
    d.add_timer(100'000, [&] {
        if (!device.joinable()) {
            device = std::thread([&] { node.run(); });
        }
        if (node.data_flowing() && d.state() != daemon::State::degraded) {
            d.ready();
        }
    });
    const int rc = d.run();
    if (device.joinable()) {
        device.join();
    }
    return rc;
}

}  // namespace ugv::gps_daemon
