#include "status_message.hpp"

#include <unistd.h>

namespace ugv::daemon {

ugv::daemon_status_t make_status_message(int64_t utime, int64_t seq, const std::string& name,
                                         const std::string& instance, int8_t state, const std::string& last_error,
                                         int64_t uptime_us,
                                         const std::vector<std::pair<std::string, int64_t>>& counters)
{
    ugv::daemon_status_t m;
    m.utime = utime;
    m.seq = seq;
    m.name = name;
    m.instance = instance;
    m.pid = static_cast<int32_t>(::getpid());
    m.state = state;
    m.last_error = last_error;
    m.uptime_us = uptime_us;
    m.ncounters = static_cast<int32_t>(counters.size());
    for (const auto& [k, v] : counters) {
        m.counter_names.push_back(k);
        m.counter_values.push_back(v);
    }
    return m;
}

}  // namespace ugv::daemon
