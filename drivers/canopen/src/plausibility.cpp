#include "ugv/canopen/plausibility.hpp"

#include <cmath>
#include <utility>

namespace ugv::canopen {

bool TpdoPlausibility::agree(const Reading& a, const Reading& b) const
{
    return a.state == b.state && std::fabs(a.angle_rad - b.angle_rad) <= max_step_rad_;
}

bool TpdoPlausibility::check(const Reading& r)
{
    const bool gap = std::exchange(gap_, false);
    const auto previous = std::exchange(previous_, r);
    const bool previous_taken = std::exchange(previous_taken_, false);
    ++since_taken_;
    bool take = previous && !gap && agree(*previous, r);
    // A held frame confirmed by this one: both must also be where the axis can be since the
    // last one taken (the same bit flipped in two frames in a row agrees with itself).
    if (take && !previous_taken && taken_)
        take = std::fabs(r.angle_rad - taken_->angle_rad) <= travel_rad_ * static_cast<double>(since_taken_) + slack_rad_;
    if (take) {
        previous_taken_ = true;
        taken_ = r;
        since_taken_ = 0;
        return true;
    }
    if (previous && !previous_taken) ++dropped_;  // held, and not confirmed
    return false;
}

void TpdoPlausibility::reset()
{
    previous_.reset();
    previous_taken_ = false;
    gap_ = false;
    taken_.reset();
    since_taken_ = 0;
}

}  // namespace ugv::canopen
