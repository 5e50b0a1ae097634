// GPS time <-> Unix time, and the host-receiver clock offset.
#pragma once

#include <cstdint>

namespace ugv::novatel {

inline constexpr int kDefaultLeapSeconds = 18;  // GPS - UTC since 2017-01-01
inline constexpr int64_t kGpsEpochUnixS = 315964800;  // 1980-01-06T00:00:00Z
inline constexpr int64_t kSecondsPerWeek = 604800;
inline constexpr int64_t kUsPerDay = 86'400'000'000;

// GPS week + ms of week -> us since the Unix epoch in UTC (GPS time minus leap seconds).
int64_t gps_to_unix_utime(uint32_t week, uint32_t ms_of_week, int leap_seconds);

// Unix us (UTC) -> GPS week and ms of week.
void unix_utime_to_gps(int64_t utime, int leap_seconds, uint32_t& week, uint32_t& ms_of_week);

// NMEA carries only the UTC time of day; the date is that of the day which puts the
// result nearest to reference_utime (the arrival time). Correct as long as the host clock
// is within 12 h of the truth, and across midnight.
int64_t utc_time_of_day_to_utime(double seconds_of_day, int64_t reference_utime);

// A civil UTC date + seconds of the day -> Unix us.
int64_t utc_date_to_utime(int year, int month, int day, double seconds_of_day);

// Is the receiver's clock good enough to stamp measurements? (time status FINE or better)
bool time_status_is_fine(uint32_t time_status);

// Tracks host arrival time minus receiver measurement time. The difference is the
// receiver's output latency plus transmission plus the host clock error; its smoothed value
// is reported in the daemon's status so a drifting host clock is visible.
class ClockOffsetTracker
{
public:
    void update(int64_t host_arrival_utime, int64_t receiver_utime);
    bool valid() const { return samples_ > 0; }
    int64_t last_us() const { return last_us_; }
    int64_t smoothed_us() const { return static_cast<int64_t>(smoothed_us_); }
    uint64_t samples() const { return samples_; }
    uint64_t jumps() const { return jumps_; }  // re-seeds after a step of more than 1 s

private:
    static constexpr double kAlpha = 1.0 / 16.0;
    static constexpr int64_t kJumpUs = 1'000'000;
    int64_t last_us_ = 0;
    double smoothed_us_ = 0;
    uint64_t samples_ = 0;
    uint64_t jumps_ = 0;
};

}  // namespace ugv::novatel
