#include "ugv/daemon/input_stamps.hpp"

#include "ugv/runtime/counters.hpp"

namespace ugv::daemon {

InputStamps::InputStamps(Daemon& d, runtime::StampLimits limits, std::function<void()> on_cleared)
    : d_(d), gate_(limits), on_cleared_(std::move(on_cleared))
{
    runtime::set_all(d_.counters(), gate_.counters());  // listed from the first STATUS on
}

bool InputStamps::accept(int input, int64_t stamp_us)
{
    const bool ok = gate_.accept(input, stamp_us, d_.bus().now_utime());
    switch (gate_.take_change()) {
    case runtime::StampChange::rejecting:
        d_.set_state(State::degraded, gate_.rejecting());
        d_.notify_status("DEGRADED: " + gate_.rejecting());
        break;
    case runtime::StampChange::cleared: on_cleared_(); break;
    case runtime::StampChange::none: break;
    }
    if (gate_.counters() != published_) {
        published_ = gate_.counters();
        runtime::set_all(d_.counters(), published_);
    }
    return ok;
}

}  // namespace ugv::daemon
