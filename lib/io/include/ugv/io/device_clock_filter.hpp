// Host time stamps from a device's own clock (a sample timer, a scan count): a filtered
// offset-and-drift model, so that the jitter of serial arrival (scheduling, USB latency,
// chunking) does not reach utime. Used by the GX1 (its u16 timer) and the LMS (its scans).
//
// The device samples on its own clock; the host sees each frame some time
// later: arrival = truth + delay, with delay >= 0 and often large. The model
//   host_time = host0 + device_elapsed + offset + drift * device_elapsed
// is fitted to the LOWER envelope of the arrivals: per block of device time the sample with
// the smallest (arrival - device_elapsed) is kept (the least delayed one), and a straight
// line is fitted by least squares to the last window of block minima. The stamp is the
// line's value, never later than the arrival itself (the truth cannot be later).
//
// An arrival well before the line (the device restarted its timer, or the host clock was
// stepped) or a device time that runs backwards restarts the model.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <deque>

namespace ugv::io {

class DeviceClockFilter
{
public:
    struct Params
    {
        double block_s = 1.0;             // device time per lower-envelope block
        std::size_t window_blocks = 60;   // blocks in the line fit (a minute)
        double restart_threshold_s = 0.05;// arrival this far before the line: restart
    };

    DeviceClockFilter() : DeviceClockFilter(Params{}) {}
    explicit DeviceClockFilter(Params p) : p_(p) {}

    // device_s: unwrapped device time (ticks * tick period); arrival_utime: host time of the
    // frame's first byte (us since the epoch). Returns the filtered host time of the sample.
    int64_t update(double device_s, int64_t arrival_utime);
    // The model's host time of a sample whose arrival time is not known, only a time after
    // it (read_utime: the sample sat in a buffer until a batched read took it). Changes
    // nothing; no later than read_utime. Before the first update(): read_utime.
    int64_t predict(double device_s, int64_t read_utime) const;
    void reset();

    double drift() const { return drift_; }         // host seconds per device second - 1
    std::size_t restarts() const { return restarts_; }

private:
    struct Point
    {
        double x, y;  // device elapsed (s), arrival minus device elapsed (s)
    };
    void refit();
    // Host time (us since the epoch) of device elapsed x with arrival-minus-device y.
    int64_t host_utime(double x, double y) const { return host0_us_ + static_cast<int64_t>(std::llround((x + y) * 1e6)); }
    void start(double device_s, int64_t arrival_utime);

    Params p_;
    bool started_ = false;
    int64_t host0_us_ = 0;
    double device0_s_ = 0;
    double last_x_ = 0;
    double block_start_x_ = 0;
    Point block_min_{0, 0};
    std::deque<Point> window_;
    double offset_ = 0, drift_ = 0;  // the fitted line y = offset_ + drift_ * x
    std::size_t restarts_ = 0;
};

}  // namespace ugv::io
