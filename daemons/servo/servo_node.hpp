// The adapter of ugv-servo: CAN transport <-> canopen::Drive <-> NodController, SERVO_COMMAND in,
// SERVO_STATE and the status counters out. Runs on the daemon's main loop (the transport's
// fd plus a control timer); a failed drive session or transport is re-initialised with
// back-off while the daemon reports DEGRADED.
//
// Wake-ups: an slcan adapter delivers each TPDO as its own serial line, and waking the loop
// for each (~200/s) was most of this daemon's CPU. Once the drive runs, the control tick
// reads the bus, and the fd is watched only during a window of kWakeWindowPeriods TPDO
// periods every frame_wakeup_period_ms: those frames are read as they arrive and fit the
// TPDO clock; the others were found by the tick some unknown time after they arrived and
// are stamped on that clock (canopen::Drive::on_frame's read_late). A transport that stamps
// the arrival itself (SocketCAN) needs no window; before the drive runs, and with SYNC, the
// fd is always watched.
#pragma once

#include <cstdint>
#include <memory>
#include <set>
#include <string>

#include "nod_controller.hpp"
#include "servo_config.hpp"
#include "ugv/canopen/drive.hpp"
#include "ugv/daemon/daemon.hpp"
#include "ugv/io/can_transport.hpp"
#include "ugv/runtime/backoff.hpp"
#include "ugv/runtime/rate_limited_log.hpp"
#include "ugv/servo_command_t.hpp"

namespace ugv::servo_daemon {

// The daemon's own counters (the drive's are canopen::DriveCounters).
struct ServoNodeCounters
{
    uint64_t bus_errors = 0;
    uint64_t reconnects = 0;
    uint64_t reinits = 0;
    uint64_t tx_failures = 0;
    uint64_t commands_accepted = 0;
    uint64_t commands_refused = 0;
    uint64_t samples = 0;
    uint64_t rx_errors = 0;

    template <class F>
    void visit(F&& f) const
    {
        f("bus_errors", bus_errors);
        f("reconnects", reconnects);
        f("reinits", reinits);
        f("tx_failures", tx_failures);
        f("commands_accepted", commands_accepted);
        f("commands_refused", commands_refused);
        f("samples", samples);
        f("rx_errors", rx_errors);
    }
};

class ServoNode
{
public:
    ServoNode(daemon::Daemon& d, ServoConfig config);
    // Opens the transport, subscribes, registers the fd and the control timer.
    void start();
    // After Daemon::run() returned: halt, then disable, within the shutdown timeout.
    void shutdown();

private:
    void open_transport();
    void close_transport(const std::string& why);
    // prompt: called because the fd became readable (the frames arrived just now).
    void drain_transport(bool prompt);
    void control_tick();
    bool want_frame_wakeups(int64_t now_us) const;
    void watch_fd(bool on);
    void flush_outgoing();
    void publish_samples();
    void log_events();
    void sync_counters();
    void on_command(const servo_command_t& msg);
    void reinitialise(const std::string& why);
    double now_s() const;

    daemon::Daemon& d_;
    ServoConfig config_;
    std::unique_ptr<io::CanTransport> transport_;
    canopen::Drive drive_;
    NodController nod_;
    runtime::Backoff backoff_;
    runtime::RateLimitedLog log_;
    bool transport_open_ = false;
    bool ever_opened_ = false;
    int registered_fd_ = -1;
    int64_t retry_at_us_ = 0;       // monotonic; when to reopen / restart
    bool was_operational_ = false;
    bool restart_scheduled_ = false;
    int64_t seq_ = 0;
    ServoNodeCounters counters_;
    int rx_errors_in_a_row_ = 0;  // without a frame between: the transport is broken
    std::set<std::string> said_once_;  // log lines said once per process
};

// ugv-servo --probe: the drive's identity, PDO resources, what can be mapped and the plan,
// printed; nothing moves (the drive stays pre-operational). 0, or 1 when no drive answers.
int probe(const ServoConfig& config);

// The daemon: the drive on the bus until a stop signal, then halt and disable.
int run(daemon::Daemon& d, ServoConfig config);

}  // namespace ugv::servo_daemon
