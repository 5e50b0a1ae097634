// The recent vehicle poses, so that each point can be placed with the pose at its own time:
// interpolate() between the two poses around that time, exact at the stored ones. No
// extrapolation: a pose outside the history is reported as such.
#pragma once

#include <cstddef>
#include <cstdint>

#include "ugv/geometry/history.hpp"
#include "ugv/geometry/pose.hpp"

namespace ugv::geometry {

class PoseHistory
{
public:
    explicit PoseHistory(int64_t span_us = 2'000'000) : poses_(span_us) {}

    enum class AddResult { added, non_finite, out_of_order };
    // Keeps poses within span_us of the newest (at least two). A non-finite pose or one not
    // newer than the last is refused. The stored orientation is normalised.
    AddResult add(const StampedPose& pose);

    enum class Lookup { ok, before_history, after_history, empty };
    // The pose at utime_us, interpolated; exact at the stored poses.
    Lookup at(int64_t utime_us, StampedPose& out) const;

    bool empty() const { return poses_.empty(); }
    std::size_t size() const { return poses_.size(); }
    int64_t oldest_us() const { return poses_.oldest().utime_us; }
    int64_t newest_us() const { return poses_.newest().utime_us; }
    const StampedPose& newest() const { return poses_.newest(); }
    void clear() { poses_.clear(); }

private:
    TimeHistory<StampedPose> poses_;
};

}  // namespace ugv::geometry
