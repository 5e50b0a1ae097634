// The distance the vehicle has driven, as a function of time, from the positions of the
// maps it has seen: how far it has gone since a cell's data was taken (its certainty decays
// with that, as with the data's age). Bounded: keeps the last max_samples positions.
#pragma once

#include <cstdint>
#include <deque>

#include <Eigen/Core>

namespace ugv::traverse {

class Odometer
{
public:
    explicit Odometer(std::size_t max_samples = 4096) : max_samples_(max_samples) {}
    // A position at utime (later than the last; an earlier or equal one restarts the
    // odometer, e.g. a log replayed again). Horizontal distance only.
    void add(int64_t utime_us, const Eigen::Vector3d& position_m);
    // Metres driven between utime_us - age_s and the newest position; what lies before the
    // oldest position kept counts from there. 0 with fewer than two positions.
    double driven_since(double age_s) const;
    void clear() { samples_.clear(); }

private:
    struct Sample { int64_t utime_us; Eigen::Vector2d xy_m; double odometer_m; };
    std::deque<Sample> samples_;
    std::size_t max_samples_;
};

}  // namespace ugv::traverse
