#include "ugv/runtime/realtime.hpp"

#include <cerrno>
#include <cstring>
#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>

namespace ugv::runtime {

std::vector<std::string> apply_realtime(const RealtimeOptions& o)
{
    std::vector<std::string> warnings;
    if (o.lock_memory && mlockall(MCL_CURRENT | MCL_FUTURE) != 0)
        warnings.push_back(std::string("mlockall refused (") + std::strerror(errno) +
                           "): memory may be paged out; set LimitMEMLOCK=infinity");
    if (o.fifo_priority > 0) {
        sched_param p{};
        p.sched_priority = o.fifo_priority;
        const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &p);
        if (rc != 0)
            warnings.push_back("SCHED_FIFO priority " + std::to_string(o.fifo_priority) + " refused (" +
                               std::strerror(rc) + "): running with normal scheduling; set LimitRTPRIO=");
    }
    if (!o.cpus.empty()) {
        cpu_set_t set;
        CPU_ZERO(&set);
        for (const int c : o.cpus)
            if (c >= 0 && c < CPU_SETSIZE) CPU_SET(c, &set);
        const int rc = pthread_setaffinity_np(pthread_self(), sizeof set, &set);
        if (rc != 0) warnings.push_back(std::string("CPU affinity refused (") + std::strerror(rc) + ")");
    }
    return warnings;
}

}  // namespace ugv::runtime
