#include "ugv/io/periodic_clock.hpp"

#include <algorithm>
#include <cmath>

namespace ugv::io {

namespace {

DeviceClockFilter::Params filter_params(double period_s)
{
    DeviceClockFilter::Params p;
    p.block_s = 0.5;           // per lower-envelope point: 19 LMS scans, 50 TPDOs
    p.window_blocks = 20;      // a 10 s fit: long enough for the drift, short for a warm mirror
    p.restart_threshold_s = period_s / 2;
    return p;
}

}  // namespace

PeriodicClock::PeriodicClock(double period_s, int periods_per_message, uint64_t restarts_so_far)
    : period_s_(period_s),
      periods_per_message_(std::max(1, periods_per_message)),
      filter_(filter_params(period_s)),
      slips_(restarts_so_far)
{
}

void PeriodicClock::reset()
{
    started_ = false;
    count_ = 0;
    late_in_a_row_ = 0;
    filter_.reset();
}

double PeriodicClock::advance(int lost_since_last)
{
    count_ += int64_t{periods_per_message_} * (1 + std::max(0, lost_since_last));
    return static_cast<double>(count_) * period_s_;
}

int64_t PeriodicClock::update(int64_t arrival_utime, int lost_since_last)
{
    const double device_s = started_ ? advance(lost_since_last) : 0.0;
    started_ = true;
    const int64_t stamp = filter_.update(device_s, arrival_utime);
    const double late_s = static_cast<double>(arrival_utime - stamp) * 1e-6;
    late_in_a_row_ = late_s > period_s_ / 2 ? late_in_a_row_ + 1 : 0;
    if (late_in_a_row_ >= kLateBeforeRestart) {
        // Every recent message half a period late: the count fell short. Start again here.
        ++slips_;
        reset();
        started_ = true;
        return filter_.update(0.0, arrival_utime);
    }
    return stamp;
}

int64_t PeriodicClock::update_read_late(int64_t read_utime, int lost_since_last)
{
    if (!started_) return update(read_utime, lost_since_last);
    return filter_.predict(advance(lost_since_last), read_utime);
}

}  // namespace ugv::io
