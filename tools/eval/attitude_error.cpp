#include "attitude_error.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace ugv::eval {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRadToDeg = 180.0 / kPi;
constexpr double kRateHalfWindowS = 0.1;

double wrap(double a) { return std::remainder(a, 2 * kPi); }

}  // namespace

TruthTrack::TruthTrack(std::vector<TruthSample> samples) : samples_(std::move(samples))
{
    std::sort(samples_.begin(), samples_.end(), [](const TruthSample& a, const TruthSample& b) { return a.utime < b.utime; });
}

std::optional<double> TruthTrack::yaw_at(int64_t utime, double max_gap_s) const
{
    const auto hi = std::lower_bound(samples_.begin(), samples_.end(), utime,
                                     [](const TruthSample& s, int64_t t) { return s.utime < t; });
    if (hi == samples_.end()) return std::nullopt;
    if (hi->utime == utime) return hi->yaw_rad;
    if (hi == samples_.begin()) return std::nullopt;
    const auto lo = hi - 1;
    if (static_cast<double>(hi->utime - lo->utime) * 1e-6 > max_gap_s) return std::nullopt;
    const double f = static_cast<double>(utime - lo->utime) / static_cast<double>(hi->utime - lo->utime);
    return wrap(lo->yaw_rad + f * wrap(hi->yaw_rad - lo->yaw_rad));
}

std::optional<TruthTrack::At> TruthTrack::at(int64_t utime, double max_gap_s) const
{
    const auto hi = std::lower_bound(samples_.begin(), samples_.end(), utime,
                                     [](const TruthSample& s, int64_t t) { return s.utime < t; });
    if (hi == samples_.end()) return std::nullopt;
    const auto lo = hi->utime == utime || hi == samples_.begin() ? hi : hi - 1;
    if (lo->utime > utime || static_cast<double>(hi->utime - lo->utime) * 1e-6 > max_gap_s) return std::nullopt;
    const double f =
        hi == lo ? 0.0 : static_cast<double>(utime - lo->utime) / static_cast<double>(hi->utime - lo->utime);
    const auto window = static_cast<int64_t>(kRateHalfWindowS * 1e6);
    const auto before = yaw_at(utime - window, max_gap_s), after = yaw_at(utime + window, max_gap_s);
    At a{};
    a.roll_rad = lo->roll_rad + f * (hi->roll_rad - lo->roll_rad);
    a.pitch_rad = lo->pitch_rad + f * (hi->pitch_rad - lo->pitch_rad);
    a.yaw_rad = wrap(lo->yaw_rad + f * wrap(hi->yaw_rad - lo->yaw_rad));
    a.speed_mps = lo->speed_mps + f * (hi->speed_mps - lo->speed_mps);
    // At the ends of the truth, the rate over the half window that exists.
    if (before && after)
        a.yaw_rate_radps = wrap(*after - *before) / (2 * kRateHalfWindowS);
    else if (after)
        a.yaw_rate_radps = wrap(*after - a.yaw_rad) / kRateHalfWindowS;
    else if (before)
        a.yaw_rate_radps = wrap(a.yaw_rad - *before) / kRateHalfWindowS;
    else
        a.yaw_rate_radps = 0.0;
    return a;
}

void ErrorStats::add(double roll_err, double pitch_err, double yaw_err)
{
    ++samples;
    roll_sum2 += roll_err * roll_err;
    pitch_sum2 += pitch_err * pitch_err;
    yaw_sum2 += yaw_err * yaw_err;
    roll_max = std::max(roll_max, std::abs(roll_err));
    pitch_max = std::max(pitch_max, std::abs(pitch_err));
    yaw_max = std::max(yaw_max, std::abs(yaw_err));
}

double ErrorStats::rms(double sum2) const
{
    return samples > 0 ? std::sqrt(sum2 / static_cast<double>(samples)) : 0.0;
}

bool AttitudeErrors::add(int64_t utime, double roll_rad, double pitch_rad, double yaw_rad)
{
    const auto t = truth_.at(utime, rules_.max_truth_gap_s);
    if (!t || !std::isfinite(roll_rad) || !std::isfinite(pitch_rad)) {
        ++unscored_;
        return false;
    }
    const double er = wrap(roll_rad - t->roll_rad), ep = wrap(pitch_rad - t->pitch_rad);
    const double ey = std::isfinite(yaw_rad) ? wrap(yaw_rad - t->yaw_rad) : 0.0;
    const Motion m = std::abs(t->yaw_rate_radps) > rules_.turn_rate_radps ? Motion::turning
                     : t->speed_mps < rules_.standing_speed_mps            ? Motion::standing
                                                                           : Motion::straight;
    by_motion_[static_cast<int>(m)].add(er, ep, ey);
    all_.add(er, ep, ey);
    return true;
}

std::string json_line(const std::string& source, const std::string& motion, const ErrorStats& s)
{
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "{\"source\": \"%s\", \"motion\": \"%s\", \"samples\": %llu, \"roll_rms_deg\": %.4f, "
                  "\"roll_max_deg\": %.4f, \"pitch_rms_deg\": %.4f, \"pitch_max_deg\": %.4f, \"yaw_rms_deg\": %.4f, "
                  "\"yaw_max_deg\": %.4f}",
                  source.c_str(), motion.c_str(), static_cast<unsigned long long>(s.samples),
                  s.rms(s.roll_sum2) * kRadToDeg, s.roll_max * kRadToDeg, s.rms(s.pitch_sum2) * kRadToDeg,
                  s.pitch_max * kRadToDeg, s.rms(s.yaw_sum2) * kRadToDeg, s.yaw_max * kRadToDeg);
    return buf;
}

}  // namespace ugv::eval
