#include "ugv/runtime/stamp_gate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <spdlog/fmt/fmt.h>

namespace ugv::runtime {

namespace {

// stamp - now without overflow, saturated to the int64 range.
int64_t saturated_difference(int64_t stamp, int64_t now)
{
    int64_t d = 0;
    if (__builtin_sub_overflow(stamp, now, &d)) {
        return stamp > now ? std::numeric_limits<int64_t>::max() : std::numeric_limits<int64_t>::min();
    }
    return d;
}

}  // namespace

StampVerdict check_stamp(int64_t stamp_us, int64_t now_us, const StampLimits& limits)
{
    // In 128 bits, the difference of any two int64 is exact.
    const __int128 d = static_cast<__int128>(stamp_us) - now_us;
    if (d > limits.max_ahead_us) return StampVerdict::ahead;
    if (d < -static_cast<__int128>(limits.max_age_us)) return StampVerdict::too_old;
    return StampVerdict::ok;
}

int64_t read_max_stamp_ahead_us(Config& cfg)
{
    return static_cast<int64_t>(std::llround(cfg.get_double("max_stamp_ahead_s", 2.0, 0.001, 3600.0) * 1e6));
}

StampSkewLimits read_stamp_skew_limits(Config& cfg, int64_t max_ahead_us)
{
    StampSkewLimits l;
    l.max_skew_us = static_cast<int64_t>(std::llround(cfg.get_double("max_stamp_skew_s", 0.05, 0.0001, 3600.0) * 1e6));
    l.max_lag_us = static_cast<int64_t>(std::llround(cfg.get_double("max_stamp_lag_s", 1.0, 0.001, 3600.0) * 1e6));
    // Beyond max_stamp_ahead_s a message is refused, so a larger skew bound would never flag.
    if (l.max_skew_us > max_ahead_us) cfg.fail("max_stamp_skew_s", "must not exceed max_stamp_ahead_s");
    return l;
}

StampChange StampGate::take_change()
{
    if (!reason_.empty() && !reported_) {
        reported_ = true;
        return StampChange::rejecting;
    }
    if (reason_.empty() && reported_) {
        reported_ = false;
        return StampChange::cleared;
    }
    return StampChange::none;
}

StampGate::StampGate(StampLimits limits, int64_t all_rejected_after_us)
    : limits_(limits), all_rejected_after_us_(all_rejected_after_us)
{
}

int StampGate::add_input(std::string name)
{
    inputs_.push_back(Input{.name = std::move(name)});
    return static_cast<int>(inputs_.size()) - 1;
}

bool StampGate::accept(int input, int64_t stamp_us, int64_t now_us)
{
    Input& in = inputs_.at(static_cast<std::size_t>(input));
    const StampVerdict v = check_stamp(stamp_us, now_us, limits_);
    if (v == StampVerdict::ok) {
        if (in.refusing) {
            in.refusing = false;
            if (in.all_refused) {
                in.all_refused = false;
                update_reason();
            }
        }
        track_skew(in, stamp_us, now_us);
        return true;
    }
    ++(v == StampVerdict::ahead ? counters_.stamps_ahead : counters_.stamps_too_old);
    if (!in.refusing) {
        in.refusing = true;
        in.first_refused_us = now_us;
    }
    in.last_refused_us = now_us;
    in.last = v;
    const double off_s = static_cast<double>(saturated_difference(stamp_us, now_us)) * 1e-6;
    const bool ahead = v == StampVerdict::ahead;
    log_.log(spdlog::level::warn, in.name + (ahead ? "/ahead" : "/old"),
             fmt::format("{}: message stamped {} {:.6g} s {} the clock: refused (max {} {} s)", in.name, stamp_us,
                         ahead ? off_s : -off_s, ahead ? "ahead of" : "behind",
                         ahead ? "ahead" : "age", static_cast<double>(ahead ? limits_.max_ahead_us : limits_.max_age_us) * 1e-6),
             now_us);
    // The refused run must itself last the interval: one bad message and then silence is a
    // stall (the daemon's health timeout), not an input that is all being refused.
    if (!in.all_refused && saturated_difference(in.last_refused_us, in.first_refused_us) >= all_rejected_after_us_) {
        in.all_refused = true;
        update_reason();
    }
    return false;
}

void StampGate::track_skew(Input& in, int64_t stamp_us, int64_t now_us)
{
    const StampSkewLimits& l = limits_.skew;
    const int64_t age = saturated_difference(now_us, stamp_us);
    const int64_t ahead = age == std::numeric_limits<int64_t>::min() ? std::numeric_limits<int64_t>::max() : -age;
    // Early: wrong at once, whatever the latency. It holds until kSkewWindowUs without one.
    if (ahead > l.max_skew_us) {
        in.early_most_us = in.early ? std::max(in.early_most_us, ahead) : ahead;
        in.early = true;
        in.last_early_us = now_us;
        ++counters_.stamps_skewed;
    } else if (in.early && saturated_difference(now_us, in.last_early_us) >= kSkewWindowUs) {
        in.early = false;
    }
    // Late: only when every stamp of a whole window was (one slow delivery is not a clock).
    if (age > l.max_lag_us) {
        in.late_least_us = in.late_run ? std::min(in.late_least_us, age) : age;
        if (!in.late_run) in.late_since_us = now_us;
        in.late_run = true;
        ++counters_.stamps_skewed;
    } else {
        in.late_run = false;
    }
    const bool late = in.late_run && saturated_difference(now_us, in.late_since_us) >= kSkewWindowUs;

    const bool was = in.skewed;
    in.skewed = in.early || late;
    in.skew_us = in.early ? in.early_most_us : late ? -in.late_least_us : 0;
    if (in.skewed != was || in.skewed) update_skew();
    if (in.skewed && !was) {
        ++counters_.clock_skew_events;
        log_.log(spdlog::level::warn, in.name + "/skew",
                 fmt::format("{}: stamps {:.6g} s {} this host's clock (max_stamp_{}_s {:g}): the clocks disagree, check "
                             "the time sync (docs/time.md)",
                             in.name, static_cast<double>(in.early ? in.skew_us : -in.skew_us) * 1e-6,
                             in.early ? "ahead of" : "behind", in.early ? "skew" : "lag",
                             static_cast<double>(in.early ? l.max_skew_us : l.max_lag_us) * 1e-6),
                 now_us);
    }
}

void StampGate::update_skew()
{
    counters_.clock_skew = 0;
    counters_.clock_skew_us = 0;
    skew_reason_.clear();
    for (const Input& in : inputs_) {
        if (!in.skewed) continue;
        counters_.clock_skew = 1;
        counters_.clock_skew_us = in.skew_us;
        skew_reason_ = fmt::format("{} stamped {:.3f} s {} the clock", in.name,
                                   static_cast<double>(in.skew_us > 0 ? in.skew_us : -in.skew_us) * 1e-6,
                                   in.skew_us > 0 ? "ahead of" : "behind");
        return;
    }
}

void StampGate::update_reason()
{
    reason_.clear();
    for (const Input& in : inputs_) {
        if (!in.all_refused) continue;
        reason_ = fmt::format("every {} message for {:.1f} s stamped {}", in.name,
                              static_cast<double>(all_rejected_after_us_) * 1e-6,
                              in.last == StampVerdict::ahead ? "too far ahead of the clock" : "older than the history");
        return;
    }
}

}  // namespace ugv::runtime
