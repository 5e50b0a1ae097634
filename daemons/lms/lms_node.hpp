// The adapter of ugv-lms: the LMS session on its own thread: opens the serial port (and reopens it after an unplug),
// runs the session until the daemon stops, and queues scans and raw bytes for the main thread.
#pragma once

#include <atomic>
#include <thread>

#include <ugv/laser_scan_t.hpp>
#include <ugv/raw_bytes_t.hpp>

#include "lms_config.hpp"
#include "ugv/daemon/daemon.hpp"
#include "ugv/io/serial_port.hpp"
#include "ugv/runtime/rate_limited_log.hpp"
#include "ugv/sick_lms2xx/session.hpp"

namespace ugv::lms_daemon {

class LmsNode
{
public:
    LmsNode(daemon::Daemon& d, const LmsConfig& config);
    ~LmsNode();
    void start();
    void join();
    // Copies the session's counters into the daemon's (main thread, from a timer).
    void publish_counters();
    bool streaming() const { return streaming_.load(); }
    double silence_timeout_s() const { return session_.silence_timeout_s(); }

private:
    void run();
    bool reopen();
    void on_state(sick_lms2xx::SessionState s, const std::string& why);
    void on_bytes(const uint8_t* data, std::size_t n, int64_t utime, bool from_device);
    // Publishes from this thread (LCM's publish is thread-safe; out() lives as long as the
    // Daemon): no hop through the main loop between the last byte and the bus.
    template <typename M>
    bool publish(const std::string& channel, const M& m);

    daemon::Daemon& d_;
    const LmsConfig& config_;
    std::atomic<int64_t>& published_;  // scans
    std::atomic<int64_t>& publish_failures_;
    io::SerialPort port_;
    sick_lms2xx::Session session_;
    runtime::RateLimitedLog log_;
    std::atomic<bool> streaming_{false};
    bool ever_streamed_ = false;  // session thread only
    int64_t scan_seq_ = 0, raw_seq_ = 0;
    std::thread thread_;
};

// The daemon: the device thread, status and systemd until a stop signal.
int run(daemon::Daemon& d, const LmsConfig& config);

}  // namespace ugv::lms_daemon
