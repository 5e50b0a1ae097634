// A processing daemon's runtime::StampGate wired to its state: while every message of one
// input is refused, the daemon is DEGRADED saying which; once one is taken again, on_cleared
// gives the daemon its own state back (RUNNING, or ugv-pose's filter state). Main thread.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "ugv/daemon/daemon.hpp"
#include "ugv/runtime/stamp_gate.hpp"

namespace ugv::daemon {

class InputStamps
{
public:
    InputStamps(Daemon& d, runtime::StampLimits limits, std::function<void()> on_cleared);

    // An input (its channel, named in the log line and the reason); returns its id.
    int add_input(std::string channel) { return gate_.add_input(std::move(channel)); }
    // True when the stamp is sane against the bus clock; else counted (STATUS) and logged.
    // A taken stamp may still raise the clock-disagreement flag (StampGate, docs/time.md).
    bool accept(int input, int64_t stamp_us);
    // Every message of some input refused for a while: the daemon says DEGRADED.
    bool refusing() const { return !gate_.rejecting().empty(); }
    const std::string& reason() const { return gate_.rejecting(); }
    const runtime::StampCounters& counters() const { return gate_.counters(); }
    // "" unless some input's stamps disagree with the clock by more than the skew bounds.
    const std::string& skewed() const { return gate_.skewed(); }

private:
    Daemon& d_;
    runtime::StampGate gate_;
    std::function<void()> on_cleared_;
    runtime::StampCounters published_;  // what STATUS has
};

}  // namespace ugv::daemon
