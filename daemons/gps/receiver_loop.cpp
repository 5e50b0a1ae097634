#include "receiver_loop.hpp"

#include <chrono>
#include <thread>
#include <vector>

#include <spdlog/spdlog.h>
#include <ugv/raw_bytes_t.hpp>

#include "lcm_messages.hpp"
#include "ugv/bus/typed.hpp"
#include "ugv/io/clock.hpp"
#include "ugv/io/serial_port.hpp"
#include "ugv/novatel/session.hpp"
#include "ugv/runtime/backoff.hpp"

namespace ugv::gps {
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

const char* kCounterNames[] = {
    "frames_binary", "frames_binary_short", "frames_ascii", "frames_ascii_short", "frames_nmea",
    "frames_reply", "frames_prompt", "crc_errors", "bad_length", "resyncs", "skipped_bytes", "unknown_ids",
    "malformed", "binary_responses", "ignored_protocol", "superseded", "fixes_published", "velocities_published",
    "reconnects", "silences", "configure_failures", "open_failures", "commands_sent", "found_by_probing",
    "clock_offset_us", "clock_offset_last_us", "clock_jumps", "time_status",
};

}  // namespace

ReceiverLoop::ReceiverLoop(daemon::Daemon& daemon, GpsConfig config)
    : daemon_(daemon), config_(std::move(config)),
      interpreter_(novatel::InterpreterConfig{config_.leap_seconds, config_.output_latency_us, config_.baud,
                                              2'000'000})
{
    for (const char* name : kCounterNames) {
        daemon_.counters()[name];  // listed from the first status message on
    }
    daemon_.set_health_timeout_us(config_.silence_timeout_us);
}

bool ReceiverLoop::wanted(novatel::FrameKind kind) const
{
    using novatel::FrameKind;
    switch (config_.protocol) {
    case Protocol::nmea: return kind == FrameKind::nmea || kind == FrameKind::reply || kind == FrameKind::prompt;
    case Protocol::novatel: return kind != FrameKind::nmea;
    case Protocol::automatic: return true;
    }
    return true;
}

void ReceiverLoop::on_message(const novatel::Decoded& m)
{
    if (!wanted(m.kind)) {
        ++ignored_;
        return;
    }
    const auto out = interpreter_.on_message(m.message, m.kind, m.arrival_utime, m.frame_bytes);
    auto& counters = daemon_.counters();
    if (out.fix) {
        bus::publish(daemon_.out(), config_.channel_fix, to_message(*out.fix, fix_seq_++));
        ++counters["fixes_published"];
        ++fixes_;
        daemon_.mark_alive();
        data_flowing_ = true;
    }
    if (out.velocity) {
        bus::publish(daemon_.out(), config_.channel_vel, to_message(*out.velocity, vel_seq_++));
        ++counters["velocities_published"];
    }
}

void ReceiverLoop::publish_raw(const uint8_t* data, std::size_t n, int64_t utime)
{
    ugv::raw_bytes_t raw{};
    raw.utime = utime;
    raw.seq = raw_seq_++;
    raw.device = config_.raw_device_name;
    raw.direction = ugv::raw_bytes_t::DIRECTION_FROM_DEVICE;
    raw.nbytes = static_cast<int32_t>(n);
    raw.data.assign(data, data + n);
    bus::publish(daemon_.out(), config_.channel_raw, raw);
}

void ReceiverLoop::update_counters()
{
    auto& c = daemon_.counters();
    const auto& s = decoder_.splitter_counters();
    for (std::size_t k = 0; k < novatel::kFrameKindCount; ++k) {
        c[std::string("frames_") + novatel::frame_kind_name(static_cast<novatel::FrameKind>(k))] =
            static_cast<int64_t>(s.frames[k]);
    }
    c["crc_errors"] = static_cast<int64_t>(s.crc_errors);
    c["bad_length"] = static_cast<int64_t>(s.bad_length);
    c["resyncs"] = static_cast<int64_t>(s.resyncs);
    c["skipped_bytes"] = static_cast<int64_t>(s.skipped_bytes);
    const auto& d = decoder_.counters();
    if (static_cast<int64_t>(d.unknown_total) != c["unknown_ids"].load()) {
        c["unknown_ids"] = static_cast<int64_t>(d.unknown_total);
        for (const auto& [id, n] : d.unknown_binary_ids) {
            c["unknown_id_" + std::to_string(id)] = static_cast<int64_t>(n);
        }
        for (const auto& [name, n] : d.unknown_names) {
            c["unknown_" + name] = static_cast<int64_t>(n);
        }
    }
    c["malformed"] = static_cast<int64_t>(d.malformed);
    c["binary_responses"] = static_cast<int64_t>(d.binary_responses);
    c["ignored_protocol"] = static_cast<int64_t>(ignored_);
    c["superseded"] = static_cast<int64_t>(interpreter_.superseded());
    const auto& clock = interpreter_.clock();
    if (clock.valid()) {
        c["clock_offset_us"] = clock.smoothed_us();
        c["clock_offset_last_us"] = clock.last_us();
        c["clock_jumps"] = static_cast<int64_t>(clock.jumps());
    }
    c["time_status"] = static_cast<int64_t>(interpreter_.last_time_status());
}

void ReceiverLoop::run()
{
    auto& counters = daemon_.counters();
    runtime::Backoff backoff;
    bool first_attempt = true;
    const auto sink = [this](const novatel::Decoded& m) { on_message(m); };
    while (!daemon_.stop_requested()) {
        if (!first_attempt) {
            sleep_unless_stopped(daemon_, backoff.next());
            if (daemon_.stop_requested()) {
                break;
            }
        }
        first_attempt = false;
        io::SerialPort port;
        if (!port.open(config_.device, config_.baud)) {
            ++counters["open_failures"];
            daemon_.set_state(daemon::State::degraded, port.last_error());
            continue;
        }
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
        const bool started = session.start(sink);
        counters["commands_sent"] += static_cast<int64_t>(session.counters().commands_sent);
        if (session.counters().found_by_probing > 0) {
            ++counters["found_by_probing"];
            spdlog::warn("{}: receiver answered at {} baud, not at the configured {}; set it back with COM", config_.device,
                         session.found_at_baud(), config_.com_baud > 0 ? config_.com_baud : config_.baud);
        }
        if (!started) {
            ++counters["configure_failures"];
            daemon_.set_state(daemon::State::degraded, "configure " + config_.device + ": " + session.error());
            update_counters();
            continue;
        }
        spdlog::info("{}: session started ({}, {} baud)", config_.device, config_.configure ? "configured" : "passive",
                     port.baud());
        novatel::Session::Status status = novatel::Session::Status::ok;
        const uint64_t fixes_at_start = fixes_;
        while (!daemon_.stop_requested()) {
            status = session.poll(kPollMs, sink);
            update_counters();
            if (status != novatel::Session::Status::ok) {
                break;
            }
            // Healthy again only once this session delivered a fix.
            if (fixes_ > fixes_at_start && daemon_.state() == daemon::State::degraded) {
                daemon_.set_state(daemon::State::running);
                backoff.reset();
            }
        }
        if (daemon_.stop_requested()) {
            break;
        }
        if (status == novatel::Session::Status::silent) {
            ++counters["silences"];
        }
        ++counters["reconnects"];
        daemon_.set_state(daemon::State::degraded, config_.device + ": " + session.error());
        port.close();
    }
}

}  // namespace ugv::gps
