// The device thread of ugv-imu: open the port, run the 3DM-GX1 session, publish imu_t, and
// recover from everything (unplug, hang-up, silence, a unit that does not answer) without
// exiting: reopen with back-off, re-initialise, and report DEGRADED meanwhile.
#pragma once

#include <cstdint>

#include "imu_config.hpp"
#include "outbox.hpp"
#include "ugv/daemon/daemon.hpp"

namespace ugv::imu_daemon {

class DeviceLoop
{
public:
    // Samples (and raw chunks) go to outbox; the main thread publishes them.
    DeviceLoop(daemon::Daemon& daemon, const ImuConfig& config, Outbox& outbox);
    // Runs until the daemon is asked to stop.
    void run();

private:
    void sleep_us(int64_t us) const;  // interruptible by a stop request
    void sync_counters(const class microstrain_gx1::Session& session);

    daemon::Daemon& d_;
    ImuConfig config_;
    Outbox& outbox_;
    int64_t seq_ = 0;
    int64_t raw_seq_ = 0;
};

}  // namespace ugv::imu_daemon
