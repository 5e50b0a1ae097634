// The adapter of ugv-gps, on a device thread of its own: open the port, start the session (configure or passive),
// decode, interpret and publish. Silence or a failed configuration: DEGRADED, the port
// stays open and is read on (configure mode configures again on it after a back-off).
// Only a device that is gone (EIO, hang-up, its node vanished or replaced) is closed and
// reopened after an exponential back-off. Never exits on a device problem; returns when
// the daemon is asked to stop.
#pragma once

#include <atomic>
#include <cstdint>

#include "gps_config.hpp"
#include "ugv/daemon/daemon.hpp"
#include "ugv/io/serial_port.hpp"
#include "ugv/novatel/decoder.hpp"
#include "ugv/novatel/interpreter.hpp"
#include "ugv/novatel/session.hpp"
#include "ugv/runtime/backoff.hpp"

namespace ugv::gps_daemon {

class GpsNode
{
public:
    GpsNode(daemon::Daemon& daemon, GpsConfig config);
    void run();  // on the device thread
    // True once a session started and a fix was published (the main thread sends READY=1).
    bool data_flowing() const { return data_flowing_.load(); }

private:
    void on_message(const novatel::Decoded& message);
    bool wanted(novatel::FrameKind kind) const;
    void update_counters(const novatel::Session* session);
    void publish_raw(const uint8_t* data, std::size_t n, int64_t utime);
    // Runs one open port until the device is gone or the daemon stops.
    void serve(io::SerialPort& port, novatel::Session& session, runtime::Backoff& backoff,
               const novatel::Decoder::Sink& sink);
    bool start_session(io::SerialPort& port, novatel::Session& session, const novatel::Decoder::Sink& sink);

    daemon::Daemon& daemon_;
    GpsConfig config_;
    novatel::Decoder decoder_;
    novatel::Interpreter interpreter_;
    int64_t fix_seq_ = 0;
    int64_t vel_seq_ = 0;
    int64_t raw_seq_ = 0;
    uint64_t ignored_ = 0;
    uint64_t fixes_ = 0;
    novatel::SessionCounters sessions_;  // the sums over the sessions that ended
    std::atomic<bool> data_flowing_{false};
};

// The daemon: the device thread, status and systemd until a stop signal.
int run(daemon::Daemon& d, const GpsConfig& config);

}  // namespace ugv::gps_daemon
