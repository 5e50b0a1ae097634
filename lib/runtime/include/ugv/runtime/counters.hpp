// Named counters of a daemon (frames ok, crc errors, resyncs, reconnects, dropped, ...),
// published in daemon_status_t. Registration order is publication order. A device thread may
// increment while the main thread publishes: the values are atomic and references stay valid.
#pragma once

#include <atomic>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace ugv::runtime {

class Counters
{
public:
    // A stable reference to the counter called name (created at 0 on first use). Create
    // every counter at start-up so that the status message lists them all from the start.
    std::atomic<int64_t>& operator[](const std::string& name);
    int64_t get(const std::string& name) const;  // 0 when absent
    std::vector<std::pair<std::string, int64_t>> snapshot() const;

private:
    mutable std::mutex mutex_;  // guards the list, not the values
    std::deque<std::pair<std::string, std::atomic<int64_t>>> items_;
};

}  // namespace ugv::runtime
