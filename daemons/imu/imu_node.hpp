// The adapter of ugv-imu, on a device thread of its own: open the port, run the 3DM-GX1 session, publish imu_t, and
// recover from everything (unplug, hang-up, silence, a unit that does not answer) without
// exiting: reopen with back-off, re-initialise, and report DEGRADED meanwhile. It publishes
// on Daemon::out() itself, as ugv-lms does: handing each sample to the main thread cost a
// second wake-up per sample, a third of this daemon's CPU (docs/performance.md).
#pragma once

#include <atomic>
#include <cstdint>

#include "imu_config.hpp"
#include "ugv/daemon/daemon.hpp"

namespace ugv::imu_daemon {

class ImuNode
{
public:
    ImuNode(daemon::Daemon& daemon, const ImuConfig& config);
    // Runs until the daemon is asked to stop.
    void run();

private:
    void sleep_us(int64_t us) const;  // interruptible by a stop request
    void sync_counters(const class microstrain_gx1::Session& session);

    daemon::Daemon& d_;
    ImuConfig config_;
    std::atomic<int64_t>& published_;
    std::atomic<int64_t>& publish_failures_;
    int64_t seq_ = 0;
    int64_t raw_seq_ = 0;
};

// The daemon: the device thread, status and systemd until a stop signal.
int run(daemon::Daemon& d, const ImuConfig& config);

}  // namespace ugv::imu_daemon
