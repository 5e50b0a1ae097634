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
    // Next to a taken frame, or confirming a held one: two frames in a row agree.
    if (previous && !gap && agree(*previous, r)) {
        previous_taken_ = true;
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
}

}  // namespace ugv::canopen
