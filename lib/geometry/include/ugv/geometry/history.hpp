// A time-ordered, bounded history of stamped samples: the storage and the bracket search
// that the pose history (lib/geometry) and the servo tilt history (lib/nodscan) share. What
// a lookup between two samples means (slerp of a pose, a line through two tilt angles,
// extrapolation or not) is the owner's, so it is not here.
#pragma once

#include <algorithm>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <deque>

namespace ugv::geometry {

template <typename Sample>
concept Stamped = requires(const Sample& s) {
    { s.utime_us } -> std::convertible_to<int64_t>;
};

template <Stamped Sample>
class TimeHistory
{
public:
    // Samples older than span_us before the newest are forgotten, but two are always kept
    // so that there is a segment to interpolate on. At most max_samples are kept whatever
    // the stamps (samples 1 us apart would otherwise fill the span): the oldest go first.
    // The default holds 100 Hz for 160 s, more than any owner's span at its sensor's rate.
    static constexpr std::size_t kDefaultMaxSamples = 16384;
    explicit TimeHistory(int64_t span_us, std::size_t max_samples = kDefaultMaxSamples)
        : span_us_(span_us), max_samples_(std::max<std::size_t>(max_samples, 2))
    {
    }

    // Appends s; false (nothing stored) when it is not newer than the newest sample.
    bool add(const Sample& s)
    {
        if (!samples_.empty() && s.utime_us <= samples_.back().utime_us) return false;
        samples_.push_back(s);
        // The oldest time kept; any stamp is taken, so the subtraction must not overflow.
        int64_t keep_from = 0;
        if (__builtin_sub_overflow(s.utime_us, span_us_, &keep_from)) keep_from = INT64_MIN;
        while (samples_.size() > 2 && samples_.front().utime_us < keep_from) samples_.pop_front();
        if (samples_.size() > max_samples_) samples_.pop_front();
        return true;
    }

    // Index of the first sample not older than utime_us; size() when all are older.
    std::size_t first_not_before(int64_t utime_us) const
    {
        const auto it = std::lower_bound(samples_.begin(), samples_.end(), utime_us,
                                         [](const Sample& s, int64_t t) { return s.utime_us < t; });
        return static_cast<std::size_t>(it - samples_.begin());
    }

    const Sample& operator[](std::size_t i) const { return samples_[i]; }
    bool empty() const { return samples_.empty(); }
    std::size_t size() const { return samples_.size(); }
    const Sample& oldest() const { return samples_.front(); }
    const Sample& newest() const { return samples_.back(); }
    int64_t span_us() const { return span_us_; }
    void clear() { samples_.clear(); }

private:
    int64_t span_us_;
    std::size_t max_samples_;
    std::deque<Sample> samples_;
};

}  // namespace ugv::geometry
