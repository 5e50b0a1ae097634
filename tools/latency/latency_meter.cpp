#include "ugv/latency/latency_meter.hpp"

#include <algorithm>
#include <cmath>

namespace ugv::latency {

bool LatencyMeter::on_to(int64_t recv_utime, int64_t start_utime)
{
    const int64_t start = start_utime >= 0 ? start_utime : last_from_;
    if (start < 0 || recv_utime < start) return false;
    samples_us_.push_back(recv_utime - start);
    return true;
}

double quantile(std::vector<int64_t> values, double q)
{
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(values.size())));
    return static_cast<double>(values[std::min(values.size() - 1, rank == 0 ? 0 : rank - 1)]);
}

LatencyMeter::Summary LatencyMeter::summary() const
{
    Summary s;
    s.samples = samples_us_.size();
    if (samples_us_.empty()) return s;
    s.p50_us = quantile(samples_us_, 0.50);
    s.p99_us = quantile(samples_us_, 0.99);
    s.max_us = static_cast<double>(*std::max_element(samples_us_.begin(), samples_us_.end()));
    s.min_us = static_cast<double>(*std::min_element(samples_us_.begin(), samples_us_.end()));
    return s;
}

}  // namespace ugv::latency
