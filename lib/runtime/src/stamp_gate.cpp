#include "ugv/runtime/stamp_gate.hpp"

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
