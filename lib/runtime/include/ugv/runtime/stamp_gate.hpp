// Time sanity at a processing daemon's inputs: a message stamped further than max_ahead_us
// ahead of the daemon's clock, or more than max_age_us behind it (older than what the
// daemon keeps), is refused, counted and logged (rate-limited). The clock is the bus's
// now_utime(): the wall clock live, the log's event time in --replay, so a replay refuses
// exactly what the live run refused. One stamp of INT64_MAX taken in would otherwise become
// the daemon's idea of "now" (docs/runtime.md, "Time stamps at the inputs").
//
// An input whose every message has been refused for all_rejected_after_us is reported by
// rejecting(), so the daemon can say DEGRADED with the reason until one is taken again.
//
// Clock disagreement, among the messages taken: a stamp ahead of the clock by more than
// max_skew_us (a measurement cannot come from the future), or every message of an input
// behind it by more than max_lag_us (more than the input's latency can be) for
// kSkewWindowUs, says the sender's clock and ours disagree: flagged in the counters
// (clock_skew, clock_skew_us) and logged, the messages still taken (docs/time.md). The flag
// clears once an input has sent no early stamp for kSkewWindowUs and a stamp that is not late.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "ugv/runtime/config.hpp"
#include "ugv/runtime/rate_limited_log.hpp"

namespace ugv::runtime {

// The bounds of the clock-disagreement flag (keys max_stamp_skew_s, max_stamp_lag_s).
struct StampSkewLimits
{
    int64_t max_skew_us = 50'000;    // stamps ahead of the clock by more: flagged
    int64_t max_lag_us = 1'000'000;  // every stamp of a window behind by more: flagged
};

struct StampLimits
{
    int64_t max_ahead_us = 2'000'000;
    int64_t max_age_us = 2'000'000;
    StampSkewLimits skew{};
};

enum class StampVerdict { ok, ahead, too_old };
enum class StampChange { none, rejecting, cleared };

// The key every processing daemon shares: max_stamp_ahead_s (default 2 s, 0.001-3600 s), in us.
int64_t read_max_stamp_ahead_us(Config& cfg);

// The keys every processing daemon shares: max_stamp_skew_s (default 0.05 s, 0.0001-3600 s,
// at most max_stamp_ahead_s) and max_stamp_lag_s (default 1 s, 0.001-3600 s), in us.
StampSkewLimits read_stamp_skew_limits(Config& cfg, int64_t max_ahead_us);

// Whether stamp_us is within [now_us - max_age_us, now_us + max_ahead_us]; free of overflow
// for every stamp and clock value (INT64_MIN and INT64_MAX included).
StampVerdict check_stamp(int64_t stamp_us, int64_t now_us, const StampLimits& limits);

struct StampCounters
{
    uint64_t stamps_ahead = 0;    // refused: further ahead of the clock than max_stamp_ahead_s
    uint64_t stamps_too_old = 0;  // refused: older than the daemon's history
    uint64_t stamps_skewed = 0;   // taken, but ahead by more than max_stamp_skew_s or behind by more than max_stamp_lag_s
    uint64_t clock_skew_events = 0;  // times an input became flagged
    int64_t clock_skew = 0;       // 1 while some input's stamps disagree with the clock (the flag)
    int64_t clock_skew_us = 0;    // how far that input's stamps are from the clock: > 0 ahead (at least), < 0 behind (at most); 0 when none

    template <class F>
    void visit(F&& f) const
    {
        f("stamps_ahead", stamps_ahead);
        f("stamps_too_old", stamps_too_old);
        f("stamps_skewed", stamps_skewed);
        f("clock_skew_events", clock_skew_events);
        f("clock_skew", clock_skew);
        f("clock_skew_us", clock_skew_us);
    }
    bool operator==(const StampCounters&) const = default;
};

class StampGate
{
public:
    static constexpr int64_t kSkewWindowUs = 500'000;

    explicit StampGate(StampLimits limits, int64_t all_rejected_after_us = 1'000'000);

    // Registers an input (a channel name, used in the log line and the reason); returns its id.
    int add_input(std::string name);
    // True when the stamp is sane; otherwise counts, logs (at most once per 5 s per input and
    // kind) and returns false. now_us: the bus clock.
    bool accept(int input, int64_t stamp_us, int64_t now_us);
    // "" while every input has taken a message since it last refused one, or refused for
    // less than all_rejected_after_us; else why (the first such input).
    const std::string& rejecting() const { return reason_; }
    // "" unless some input's stamps disagree with the clock (the flag above); else which.
    const std::string& skewed() const { return skew_reason_; }
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
        bool early = false;          // a stamp ahead by more than max_skew_us within kSkewWindowUs
        int64_t last_early_us = 0;   // when the last one came
        int64_t early_most_us = 0;   // the most it was ahead in this episode
        bool late_run = false;       // every stamp since late_since_us behind by more than max_lag_us
        int64_t late_since_us = 0;
        int64_t late_least_us = 0;   // the least it was behind in this run
        bool skewed = false;
        int64_t skew_us = 0;         // > 0 ahead, < 0 behind, while skewed
    };
    void update_reason();
    void track_skew(Input& in, int64_t stamp_us, int64_t now_us);
    void update_skew();

    StampLimits limits_;
    int64_t all_rejected_after_us_;
    std::vector<Input> inputs_;
    StampCounters counters_;
    RateLimitedLog log_;
    std::string reason_;
    std::string skew_reason_;
    bool reported_ = false;
};

}  // namespace ugv::runtime
