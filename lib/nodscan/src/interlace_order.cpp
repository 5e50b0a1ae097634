#include "ugv/nodscan/interlace_order.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace ugv::nodscan {

double InterlaceResult::margin() const
{
    if (best < 0 || runner_up < 0) return 1.0;
    const double b = candidates[static_cast<std::size_t>(best)].zigzag_rms_m;
    const double r = candidates[static_cast<std::size_t>(runner_up)].zigzag_rms_m;
    return b > 0.0 ? r / b : (r > 0.0 ? INFINITY : 1.0);
}

InterlaceDetector::InterlaceDetector(InterlaceConfig config)
    : config_(config), servo_(10'000'000), assembler_(config.assembler)
{
    result_.candidates.push_back({"as published", 0.0, 0});
    sum_sq_.push_back(0.0);
}

void InterlaceDetector::add_servo(const TiltSample& sample)
{
    servo_.add(sample);
    score_ready(false);
}

void InterlaceDetector::start_candidates(int sweeps)
{
    sweeps_ = sweeps;
    std::array<int8_t, ScanView::kMaxSweeps> order{};
    std::iota(order.begin(), order.begin() + sweeps, int8_t{0});
    do {
        orders_.push_back(order);
        std::string name;
        for (int k = 0; k < sweeps; ++k) name += static_cast<char>('0' + order[static_cast<std::size_t>(k)]);
        result_.candidates.push_back({name, 0.0, 0});
        sum_sq_.push_back(0.0);
    } while (std::next_permutation(order.begin(), order.begin() + sweeps));
}

void InterlaceDetector::add_scan(const ScanView& scan)
{
    int sweeps = scan.sweeps > 1 ? scan.sweeps : 1;
    if (scan.sweeps <= 1 && scan.angle_increment > 0.0) {
        const double per_sweep = config_.degrees_per_sweep * M_PI / 180.0 / scan.angle_increment;
        sweeps = static_cast<int>(std::clamp(std::lround(per_sweep), 1L, static_cast<long>(ScanView::kMaxSweeps)));
    }
    if (sweeps_ == 0) start_candidates(sweeps);
    if (sweeps != sweeps_ || scan.n < 3) {
        ++result_.scans_skipped;
        return;
    }
    Pending p;
    p.view = scan;
    p.ranges.assign(scan.ranges, scan.ranges + scan.n);
    p.view.ranges = nullptr;
    p.last_beam_utime = ScanAssembler::last_beam_utime(scan);
    pending_.push_back(std::move(p));
    score_ready(false);
}

void InterlaceDetector::score_ready(bool all)
{
    while (!pending_.empty() && (all || servo_.newest_utime() >= pending_.front().last_beam_utime)) {
        score(pending_.front());
        pending_.pop_front();
    }
}

void InterlaceDetector::score(const Pending& p)
{
    ScanView published = p.view;
    published.ranges = p.ranges.data();
    const double period = published.sweeps > 1 ? published.sweep_period : config_.mirror_period_s;
    bool scored = false;
    for (std::size_t c = 0; c < result_.candidates.size(); ++c) {
        ScanView v = published;
        if (c > 0) {
            // Re-timed: sweep k takes phase order[k], the mirror's pace within a sweep, and the
            // last measured beam where the scan put it.
            if (!v.set_sweeps(orders_[c - 1].data(), sweeps_, period)) continue;
            v.time_increment = published.angle_increment / (2.0 * M_PI) * period;
            v.utime = 0;
            v.utime = p.last_beam_utime - static_cast<int64_t>(std::llround(v.span_s() * 1e6));
        }
        assembler_.assemble(v, servo_, cloud_);
        z_.assign(v.n, 0.0);
        has_z_.assign(v.n, 0);
        for (std::size_t k = 0; k < cloud_.size(); ++k) {
            if (cloud_.range[k] > config_.max_range_m) continue;
            z_[cloud_.beam[k]] = cloud_.z[k];
            has_z_[cloud_.beam[k]] = 1;
        }
        OrderScore& s = result_.candidates[c];
        for (std::size_t i = 1; i + 1 < v.n; ++i) {
            if (!has_z_[i - 1] || !has_z_[i] || !has_z_[i + 1]) continue;
            const double d = z_[i] - 0.5 * (z_[i - 1] + z_[i + 1]);
            if (std::abs(d) > config_.max_second_difference_m) continue;
            sum_sq_[c] += d * d;
            ++s.triples;
            scored = true;
        }
    }
    if (scored)
        ++result_.scans;
    else
        ++result_.scans_skipped;
}

InterlaceResult InterlaceDetector::finish()
{
    score_ready(true);
    InterlaceResult r = result_;
    for (std::size_t c = 0; c < r.candidates.size(); ++c) {
        OrderScore& s = r.candidates[c];
        s.zigzag_rms_m = s.triples > 0 ? std::sqrt(sum_sq_[c] / static_cast<double>(s.triples)) : NAN;
        if (c == 0 || s.triples == 0) continue;
        const auto better = [&](int other) {
            return other < 0 || s.zigzag_rms_m < r.candidates[static_cast<std::size_t>(other)].zigzag_rms_m;
        };
        if (better(r.best)) {
            r.runner_up = r.best;
            r.best = static_cast<int>(c);
        } else if (better(r.runner_up)) {
            r.runner_up = static_cast<int>(c);
        }
    }
    return r;
}

}  // namespace ugv::nodscan
