// The plumbing every ugv daemon shares, so that each daemon's main() is config -> library ->
// bus and nothing else:
//   - the command line (CLI11): --config, --lcm-url, --log-level, --print-config, --version,
//     --instance, and for processing daemons --replay LOG --out LOG;
//   - the TOML config (ugv::runtime::Config) with keys common to all daemons
//     (status_channel, [realtime]) and exit status 2 with `FILE: KEY: why` on any error;
//   - spdlog to stderr; SIGINT/SIGTERM -> STOPPING=1 and a clean return from run();
//   - sd_notify READY=1, STATUS=, WATCHDOG=1 while RUNNING with data within the timeout, or
//     while DEGRADED (recovering); a hung loop or a silent stall stops the pings;
//   - the 1 Hz daemon_status_t on STATUS_<NAME> with the named counters;
//   - the state that STATUS reports (docs/runtime.md, "What the state means"): the daemon
//     declares its output and marks it each time it publishes it (mark_output); RUNNING is
//     reported only while that output flows, DEGRADED with a reason when it stops or when
//     the daemon says so (set_state), and STARTING only until startup_timeout_s.
//
// Threads: run() is the main thread: it polls the bus fd, the fds added with add_fd(), the
// timers and the signal pipe. A daemon may run its device session on a thread of its own;
// from there it may call publish through out(), counters(), set_state(), mark_output() and
// stop_requested(), which are thread-safe. Everything else belongs to the main thread.
//
//   int main(int argc, char** argv) {
//       ugv::daemon::Daemon d({.name = "ugv-lms", .status_channel = "STATUS_LMS"}, argc, argv);
//       auto device = d.config().get_string("device", "/dev/ugv/lms");
//       d.start();            // rejects unknown keys, --print-config, real-time, opens the bus
//       ... subscribe on d.bus(), add_fd/add_timer, start a device thread ...
//       return d.run();
//   }
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "ugv/bus/bus.hpp"
#include "ugv/runtime/config.hpp"
#include "ugv/runtime/counters.hpp"
#include "ugv/runtime/notify.hpp"

namespace ugv::daemon {

struct Options
{
    std::string name;                // "ugv-lms"
    std::string status_channel;      // default STATUS_<NAME>; config key status_channel
    bool processing = false;         // offers --replay LOG --out LOG
    std::string default_config = ""; // default --config path ("" = run on defaults if absent)
    // Default of the config key bus_batch_ms: 0 = take each LCM message as it arrives; N > 0 =
    // wake for the bus at most every N ms and take everything that came meanwhile. Every
    // subscriber receives every datagram on the group (~360/s with the whole stack), and on a
    // small computer each wake-up costs more than the message: daemons whose inputs are
    // consumed at a slower pace (a 10 Hz pose, 2 Hz maps, a rare servo command) batch.
    int bus_batch_ms = 0;
};

enum class State { starting, running, degraded, fault, stopping };

class Daemon
{
public:
    // Parses the command line and loads the config. On --help/--version prints and exits 0;
    // on a bad flag or config file prints one line and exits 2.
    Daemon(Options options, int argc, char** argv);
    ~Daemon();

    // The daemon's config: read every key, then call start().
    runtime::Config& config() { return *config_; }
    // Rejects unknown keys (exit 2), prints the effective config and exits 0 on
    // --print-config, applies [realtime], opens the bus (exit 2 with one line on failure).
    void start();

    bus::Bus& bus() { return *in_; }  // subscribe here (live, or the --replay log)
    // Publish here (live, or the --out log). Valid until the Daemon is destroyed, also after
    // run() returns (to flush what is pending at the end of a replay); the --out log is
    // closed by the destructor.
    bus::Bus& out() { return *out_; }
    bool replaying() const { return replaying_; }
    const std::string& instance() const { return instance_; }
    const std::string& name() const { return options_.name; }

    runtime::Counters& counters() { return counters_; }

    // The daemon's own view of its state, and the reason. DEGRADED and FAULT are reported at
    // once; RUNNING (and STARTING) only as the output allows: RUNNING while it flows, else
    // STARTING until the start-up deadline, else DEGRADED ("no <output> for N s", with the
    // last reason given). The reason is kept until another non-empty one replaces it.
    void set_state(State state, const std::string& error = "");
    // The state reported now (what STATUS carries).
    State state() const { return state_.load(); }
    // What flows means for this daemon (a channel name, "maps updated by new points") and
    // how long it may pause before the daemon is not RUNNING (also the watchdog's health
    // timeout). Call before run().
    void declare_output(std::string what, int64_t stall_us);
    // The output was published: it flows when two marks came within stall_us of each other,
    // the last within stall_us of now (so one stray message among garbage is not RUNNING).
    void mark_output();
    // READY=1 (once) and the daemon's view RUNNING; the state is RUNNING once output flows.
    void ready();
    // A one-line STATUS= for systemd (also logged at debug level).
    void notify_status(const std::string& line);

    void add_fd(int fd, std::function<void()> on_readable);
    void remove_fd(int fd);
    // Calls fn every period_us of wall-clock time (monotonic), from the main loop; up to
    // 0.5 ms early when another timer wakes the loop (so timers share wake-ups).
    void add_timer(int64_t period_us, std::function<void()> fn);
    bool stop_requested() const;
    void request_stop();
    // The main loop. Live: until SIGINT/SIGTERM, then STOPPING=1, and returns 0.
    // Replay: dispatches the whole log, then returns 0.
    int run();

private:
    struct Timer;
    void publish_status();
    void on_watchdog();
    // Derives the reported state from the daemon's view and the output's marks (main thread).
    void update_state();
    void report(State s, const std::string& why);

    Options options_;
    std::unique_ptr<runtime::Config> config_;
    std::unique_ptr<bus::Bus> in_;
    std::unique_ptr<bus::Bus> out_log_;  // --out (replay only)
    bus::Bus* out_ = nullptr;            // in_ (live) or out_log_ (replay)
    std::string lcm_url_, replay_path_, out_path_, instance_, log_level_;
    bool print_config_ = false;
    bool replaying_ = false;
    runtime::Counters counters_;
    runtime::Notifier notifier_;
    std::atomic<State> state_{State::starting};      // reported
    std::atomic<State> requested_{State::starting};  // the daemon's own view (set_state)
    std::atomic<bool> stop_flag_{false};
    std::mutex error_mutex_;
    std::string last_error_;   // what STATUS carries
    std::string reason_;       // the daemon's last reason (set_state)
    std::string output_ = "output";
    std::atomic<int64_t> last_alive_us_{0};
    std::atomic<int64_t> prev_alive_us_{0};
    int64_t health_timeout_us_ = 2'000'000;
    int64_t startup_timeout_us_ = 30'000'000;
    int64_t bus_batch_us_ = 0;
    int64_t start_us_ = 0;
    int64_t status_seq_ = 0;
    std::string status_channel_;
    std::atomic<bool> ready_sent_{false};
    std::vector<std::pair<int, std::function<void()>>> fds_;
    std::vector<std::unique_ptr<Timer>> timers_;
};

}  // namespace ugv::daemon
