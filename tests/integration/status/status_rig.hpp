// What the STATUS tests share (issue 23, "STATUS tells the truth"): a listener on the test's
// own LCM port that keeps every STATUS of one daemon (state, last error, counters), and
// inputs stamped with the wall clock, as live producers stamp them.
#pragma once

#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <ugv/daemon_status_t.hpp>

#include "ugv/bus/typed.hpp"
#include "ugv/io/clock.hpp"
#include "ugv_test/process.hpp"

namespace ugv::test::status {

constexpr int8_t kStarting = daemon_status_t::STATE_STARTING;
constexpr int8_t kRunning = daemon_status_t::STATE_RUNNING;
constexpr int8_t kDegraded = daemon_status_t::STATE_DEGRADED;

class Listener
{
public:
    Listener(const std::string& url, const std::string& status_channel) : bus_(bus::open_live(url))
    {
        bus::subscribe<daemon_status_t>(*bus_, status_channel, [this](const std::string&, const daemon_status_t& m, int64_t) {
            status = m;
            states.push_back(m.state);
        });
    }
    bus::Bus& bus() { return *bus_; }
    // Handles traffic, calling tick() every 10 ms, until pred() holds or timeout_s passes.
    bool until(const std::function<bool()>& pred, double timeout_s, const std::function<void()>& tick = nullptr)
    {
        const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
        auto next_tick = std::chrono::steady_clock::now();
        while (!pred() && std::chrono::steady_clock::now() < end) {
            if (tick && std::chrono::steady_clock::now() >= next_tick) {
                tick();
                next_tick += std::chrono::milliseconds(10);
            }
            bus_->handle(5);
        }
        return pred();
    }
    void for_seconds(double s, const std::function<void()>& tick = nullptr)
    {
        until([] { return false; }, s, tick);
    }
    bool state_is(int8_t s) const { return !states.empty() && status.state == s; }
    bool saw(int8_t s) const { return std::find(states.begin(), states.end(), s) != states.end(); }
    bool error_has(const std::string& text) const { return status.last_error.find(text) != std::string::npos; }
    int64_t counter(const std::string& name) const
    {
        for (int i = 0; i < status.ncounters; ++i)
            if (status.counter_names[static_cast<std::size_t>(i)] == name)
                return status.counter_values[static_cast<std::size_t>(i)];
        return -1;
    }
    // The states seen since `from` (an index into states).
    bool saw_since(std::size_t from, int8_t s) const
    {
        return std::find(states.begin() + static_cast<std::ptrdiff_t>(std::min(from, states.size())), states.end(), s) !=
               states.end();
    }

    daemon_status_t status{};
    std::vector<int8_t> states;

private:
    std::unique_ptr<bus::Bus> bus_;
};

// Calls fn at most every period_us of wall time (for the inputs a test publishes).
class Every
{
public:
    explicit Every(int64_t period_us) : period_us_(period_us) {}
    template <typename F>
    void operator()(F&& fn)
    {
        const int64_t now = io::monotonic_us();
        if (now < next_us_) return;
        next_us_ = std::max(next_us_ + period_us_, now - period_us_);
        fn();
    }

private:
    int64_t period_us_;
    int64_t next_us_ = 0;
};

}  // namespace ugv::test::status
