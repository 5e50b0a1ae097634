// Time sanity at a processing daemon's inputs: a message stamped further than max_ahead_us
// ahead of the daemon's clock, or more than max_age_us behind it (older than what the
// daemon keeps), is refused, counted and logged (rate-limited). The clock is the bus's
// now_utime(): the wall clock live, the log's event time in --replay, so a replay refuses
// exactly what the live run refused. One stamp of INT64_MAX taken in would otherwise become
// the daemon's idea of "now" (docs/runtime.md, "Time stamps at the inputs").
//
// An input whose every message has been refused for all_rejected_after_us is reported by
// rejecting(), so the daemon can say DEGRADED with the reason until one is taken again.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "ugv/runtime/config.hpp"
#include "ugv/runtime/rate_limited_log.hpp"

namespace ugv::runtime {

struct StampLimits
{
    int64_t max_ahead_us = 2'000'000;
    int64_t max_age_us = 2'000'000;
};

enum class StampVerdict { ok, ahead, too_old };
enum class StampChange { none, rejecting, cleared };

// The key every processing daemon shares: max_stamp_ahead_s (default 2 s, 0.001-3600 s), in us.
int64_t read_max_stamp_ahead_us(Config& cfg);

// Whether stamp_us is within [now_us - max_age_us, now_us + max_ahead_us]; free of overflow
// for every stamp and clock value (INT64_MIN and INT64_MAX included).
StampVerdict check_stamp(int64_t stamp_us, int64_t now_us, const StampLimits& limits);

struct StampCounters
{
    uint64_t stamps_ahead = 0;    // refused: further ahead of the clock than max_stamp_ahead_s
    uint64_t stamps_too_old = 0;  // refused: older than the daemon's history

    template <class F>
    void visit(F&& f) const
    {
        f("stamps_ahead", stamps_ahead);
        f("stamps_too_old", stamps_too_old);
    }
};

class StampGate
{
public:
    explicit StampGate(StampLimits limits, int64_t all_rejected_after_us = 1'000'000);

    // Registers an input (a channel name, used in the log line and the reason); returns its id.
    int add_input(std::string name);
    // True when the stamp is sane; otherwise counts, logs (at most once per 5 s per input and
    // kind) and returns false. now_us: the bus clock.
    bool accept(int input, int64_t stamp_us, int64_t now_us);
    // "" while every input has taken a message since it last refused one, or refused for
    // less than all_rejected_after_us; else why (the first such input).
    const std::string& rejecting() const { return reason_; }
    // Once per edge: rejecting when rejecting() became non-empty, cleared when it became empty
    // again, since the last call (the daemon sets DEGRADED, then its own state back).
    StampChange take_change();

    const StampCounters& counters() const { return counters_; }
    const StampLimits& limits() const { return limits_; }

private:
    struct Input
    {
        std::string name;
        bool refusing = false;     // refused since the last one taken
        int64_t first_refused_us = 0;
        int64_t last_refused_us = 0;
        bool all_refused = false;  // refusing for at least all_rejected_after_us
        StampVerdict last = StampVerdict::ok;
    };
    void update_reason();

    StampLimits limits_;
    int64_t all_rejected_after_us_;
    std::vector<Input> inputs_;
    StampCounters counters_;
    RateLimitedLog log_;
    std::string reason_;
    bool reported_ = false;
};

}  // namespace ugv::runtime
