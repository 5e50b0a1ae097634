#include "ugv/novatel/gps_time.hpp"

#include <chrono>
#include <cmath>
#include <cstdlib>

#include "ugv/novatel/enums.hpp"

namespace ugv::novatel {

int64_t gps_to_unix_utime(uint32_t week, uint32_t ms_of_week, int leap_seconds)
{
    const int64_t gps_s = kGpsEpochUnixS + static_cast<int64_t>(week) * kSecondsPerWeek - leap_seconds;
    return gps_s * 1'000'000 + static_cast<int64_t>(ms_of_week) * 1000;
}

void unix_utime_to_gps(int64_t utime, int leap_seconds, uint32_t& week, uint32_t& ms_of_week)
{
    const int64_t gps_ms = (utime / 1000) - (kGpsEpochUnixS - leap_seconds) * 1000;
    week = static_cast<uint32_t>(gps_ms / (kSecondsPerWeek * 1000));
    ms_of_week = static_cast<uint32_t>(gps_ms % (kSecondsPerWeek * 1000));
}

int64_t utc_time_of_day_to_utime(double seconds_of_day, int64_t reference_utime)
{
    const int64_t day_start = (reference_utime / kUsPerDay) * kUsPerDay;
    int64_t t = day_start + std::llround(seconds_of_day * 1e6);
    if (t - reference_utime > kUsPerDay / 2) {
        t -= kUsPerDay;
    } else if (reference_utime - t > kUsPerDay / 2) {
        t += kUsPerDay;
    }
    return t;
}

int64_t utc_date_to_utime(int year, int month, int day, double seconds_of_day)
{
    using namespace std::chrono;
    const sys_days d = year_month_day{std::chrono::year{year}, std::chrono::month{static_cast<unsigned>(month)},
                                      std::chrono::day{static_cast<unsigned>(day)}};
    const int64_t day_us = static_cast<int64_t>(d.time_since_epoch().count()) * kUsPerDay;
    return day_us + std::llround(seconds_of_day * 1e6);
}

bool time_status_is_fine(uint32_t s)
{
    return s == time_status::fine || s == time_status::finebackupsteering || s == time_status::finesteering ||
           s == time_status::sattime;
}

void ClockOffsetTracker::update(int64_t host_arrival_utime, int64_t receiver_utime)
{
    last_us_ = host_arrival_utime - receiver_utime;
    if (samples_ == 0) {
        smoothed_us_ = static_cast<double>(last_us_);
    } else if (std::llabs(last_us_ - static_cast<int64_t>(smoothed_us_)) > kJumpUs) {
        // The host clock was stepped (NTP) or the receiver's time jumped: start again.
        smoothed_us_ = static_cast<double>(last_us_);
        ++jumps_;
    } else {
        smoothed_us_ += kAlpha * (static_cast<double>(last_us_) - smoothed_us_);
    }
    ++samples_;
}

}  // namespace ugv::novatel
