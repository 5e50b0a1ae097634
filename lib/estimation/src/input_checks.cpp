#include "ugv/estimation/input_checks.hpp"

#include <cmath>

namespace ugv::estimation {

namespace {

// Beyond this a stamp is no time at all (year ~146,000), and the estimator's arithmetic on
// stamps (plus a period, a timeout) must not overflow.
constexpr int64_t kMaxUtime = int64_t{1} << 62;

bool sane_time(int64_t utime)
{
    return utime > 0 && utime < kMaxUtime;
}

bool nan_or_nonnegative(double x)
{
    return std::isnan(x) || (std::isfinite(x) && x >= 0.0);
}

}  // namespace

int quality_rank(FixQuality q)
{
    switch (q) {
    case FixQuality::single: return 1;
    case FixQuality::sbas: return 2;
    case FixQuality::dgps: return 3;
    case FixQuality::rtk_float: return 4;
    case FixQuality::rtk_fixed: return 5;
    case FixQuality::none:
    case FixQuality::dead_reckoning:
    case FixQuality::unknown: return 0;
    }
    return 0;
}

bool is_valid(const GpsFix& f)
{
    return sane_time(f.utime) && std::isfinite(f.latitude_deg) && std::isfinite(f.longitude_deg) &&
           std::isfinite(f.height_m) && std::fabs(f.latitude_deg) <= 90.0 && std::fabs(f.longitude_deg) <= 180.0 &&
           nan_or_nonnegative(f.sigma_north_m) && nan_or_nonnegative(f.sigma_east_m) &&
           nan_or_nonnegative(f.sigma_up_m);
}

bool is_valid(const GpsVelocity& v)
{
    return sane_time(v.utime) && std::isfinite(v.horizontal_speed_mps) && v.horizontal_speed_mps >= 0.0 &&
           std::isfinite(v.track_rad) && (std::isnan(v.vertical_speed_mps) || std::isfinite(v.vertical_speed_mps));
}

bool is_valid(const ImuSample& s)
{
    if (!sane_time(s.utime) || !(s.has_orientation || s.has_rate || s.has_accel)) {
        return false;
    }
    if (s.has_orientation) {
        if (!s.orientation.coeffs().allFinite()) {
            return false;
        }
        const double n = s.orientation.norm();
        if (n < 0.9 || n > 1.1) {
            return false;
        }
        if (!(std::isnan(s.orientation_sigma_rad) ||
              (std::isfinite(s.orientation_sigma_rad) && s.orientation_sigma_rad > 0.0))) {
            return false;
        }
    }
    if (s.has_rate && !s.rate_rps.allFinite()) {
        return false;
    }
    if (s.has_accel && !s.accel_mps2.allFinite()) {
        return false;
    }
    return true;
}

}  // namespace ugv::estimation
