#include "ugv/io/device_clock_filter.hpp"

#include <algorithm>
#include <cmath>

namespace ugv::io {

void DeviceClockFilter::reset()
{
    started_ = false;
    window_.clear();
    offset_ = drift_ = 0;
}

void DeviceClockFilter::start(double device_s, int64_t arrival_utime)
{
    window_.clear();
    started_ = true;
    host0_us_ = arrival_utime;
    device0_s_ = device_s;
    last_x_ = 0;
    block_start_x_ = 0;
    block_min_ = {0, 0};
    offset_ = 0;
    drift_ = 0;
}

void DeviceClockFilter::refit()
{
    // Least squares over the completed blocks' minima, centred on the mean x for conditioning.
    const double n = static_cast<double>(window_.size());
    double mx = 0, my = 0;
    for (const Point& q : window_) {
        mx += q.x;
        my += q.y;
    }
    mx /= n;
    my /= n;
    double sxx = 0, sxy = 0;
    for (const Point& q : window_) {
        sxx += (q.x - mx) * (q.x - mx);
        sxy += (q.x - mx) * (q.y - my);
    }
    drift_ = sxx > 0 ? sxy / sxx : 0.0;
    offset_ = my - drift_ * mx;
}

int64_t DeviceClockFilter::update(double device_s, int64_t arrival_utime)
{
    if (!started_) start(device_s, arrival_utime);
    double x = device_s - device0_s_;
    double y = static_cast<double>(arrival_utime - host0_us_) * 1e-6 - x;
    if (x < last_x_ || y < offset_ + drift_ * x - p_.restart_threshold_s) {
        ++restarts_;
        start(device_s, arrival_utime);
        x = 0;
        y = 0;
    }
    last_x_ = x;

    if (x - block_start_x_ >= p_.block_s) {
        window_.push_back(block_min_);
        while (window_.size() > p_.window_blocks) window_.pop_front();
        block_start_x_ = x;
        block_min_ = {x, y};
        // The drift needs a baseline of at least two blocks to be better than noise.
        if (window_.size() >= 2) refit();
    } else if (y < block_min_.y) {
        block_min_ = {x, y};
    }
    if (window_.size() < 2) {
        // Warm-up: a pure offset at the least delayed sample so far.
        drift_ = 0;
        offset_ = block_min_.y;
        for (const Point& q : window_) offset_ = std::min(offset_, q.y);
    }
    // The line must not pass above the least delayed sample of the current block.
    offset_ = std::min(offset_, block_min_.y - drift_ * block_min_.x);
    const double y_hat = std::min(offset_ + drift_ * x, y);
    return host_utime(x, y_hat);
}

int64_t DeviceClockFilter::predict(double device_s, int64_t read_utime) const
{
    if (!started_) return read_utime;
    const double x = device_s - device0_s_;
    return std::min(host_utime(x, offset_ + drift_ * x), read_utime);
}

}  // namespace ugv::io
