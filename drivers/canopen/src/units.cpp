#include "ugv/canopen/units.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace ugv::canopen {

double UnitConversion::counts_per_rad() const
{
    return counts_per_rev * gear_ratio / (2.0 * std::numbers::pi);
}

double UnitConversion::to_rad(int64_t counts) const
{
    return direction * static_cast<double>(counts - zero_offset) / counts_per_rad();
}

double UnitConversion::to_rad_s(double counts_per_s) const { return direction * counts_per_s / counts_per_rad(); }

int32_t UnitConversion::to_counts(double rad) const
{
    const double c = std::round(direction * rad * counts_per_rad()) + static_cast<double>(zero_offset);
    constexpr double lo = std::numeric_limits<int32_t>::min();
    constexpr double hi = std::numeric_limits<int32_t>::max();
    if (!(c >= lo)) return std::numeric_limits<int32_t>::min();  // also NaN
    if (c > hi) return std::numeric_limits<int32_t>::max();
    return static_cast<int32_t>(c);
}

uint32_t UnitConversion::to_counts_rate(double rad_per_s) const
{
    const double c = std::round(std::fabs(rad_per_s) * counts_per_rad());
    if (!(c >= 0.0)) return 0;
    if (c > static_cast<double>(std::numeric_limits<uint32_t>::max())) return std::numeric_limits<uint32_t>::max();
    return static_cast<uint32_t>(c);
}

}  // namespace ugv::canopen
