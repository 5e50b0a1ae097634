// Named counters of a daemon (frames ok, crc errors, resyncs, reconnects, dropped, ...),
// published in daemon_status_t. Registration order is publication order. A device thread may
// increment while the main thread publishes: the values are atomic and references stay valid.
#pragma once

#include <atomic>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <string_view>
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

// A library's counter struct names each of its fields once, in a member
//   template <class F> void visit(F&& f) const { f("frames", frames); f("resyncs", resyncs); }
// (values convertible to int64_t; a struct may also name counters it discovers at run time).
// The daemon then publishes all of them without a list of its own.
template <class S>
void set_all(Counters& out, const S& counters)
{
    counters.visit([&out](std::string_view name, auto value) { out[std::string(name)] = static_cast<int64_t>(value); });
}

// The names a counter struct visits, in order (tests: every one appears in the STATUS message).
template <class S>
std::vector<std::string> counter_names(const S& counters)
{
    std::vector<std::string> names;
    counters.visit([&names](std::string_view name, auto) { names.emplace_back(name); });
    return names;
}

}  // namespace ugv::runtime
