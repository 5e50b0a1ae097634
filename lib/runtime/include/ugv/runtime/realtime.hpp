// Optional real-time set-up. Each step that the system refuses produces a warning line and
// the daemon goes on (a bench PC without rtprio must still run).
#pragma once

#include <string>
#include <vector>

namespace ugv::runtime {

struct RealtimeOptions
{
    bool lock_memory = false;   // mlockall(MCL_CURRENT | MCL_FUTURE)
    int fifo_priority = 0;      // SCHED_FIFO priority 1..99, 0 = leave the scheduler alone
    std::vector<int> cpus;      // CPU affinity, empty = leave alone
};

// Applies what is asked; returns one warning line per step that failed (empty = all applied).
std::vector<std::string> apply_realtime(const RealtimeOptions& options);

}  // namespace ugv::runtime
