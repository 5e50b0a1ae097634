// A short history of poses so that each point is transformed with the pose at its own time
// (linear position, slerp orientation, linear covariance between the two poses around it).
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>

#include "ugv/terrain/pose.hpp"

namespace ugv::terrain {

class PoseHistory
{
public:
    explicit PoseHistory(int64_t span_us = 2'000'000) : span_us_(span_us) {}

    enum class AddResult { added, non_finite, out_of_order };
    // Keeps poses within span_us of the newest. A non-finite pose or one not newer than the
    // last is refused.
    AddResult add(const Pose& pose);

    enum class Lookup { ok, before_history, after_history, empty };
    // The pose at utime_us, interpolated; exact at the stored poses.
    Lookup at(int64_t utime_us, Pose& out) const;

    bool empty() const { return poses_.empty(); }
    std::size_t size() const { return poses_.size(); }
    int64_t oldest_us() const { return poses_.front().utime_us; }
    int64_t newest_us() const { return poses_.back().utime_us; }
    const Pose& newest() const { return poses_.back(); }
    void clear() { poses_.clear(); }

private:
    int64_t span_us_;
    std::deque<Pose> poses_;
};

// Interpolates between a (fraction 0) and b (fraction 1).
Pose interpolate(const Pose& a, const Pose& b, double fraction);

}  // namespace ugv::terrain
