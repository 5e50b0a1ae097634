// Which inputs the estimator refuses outright: non-finite or out-of-range values and
// impossible time stamps. Everything refused here is counted as non_finite.
#pragma once

#include "ugv/estimation/inputs.hpp"

namespace ugv::estimation {

// utime: 0 < utime < 2^62 for every input.
// lat/lon/height finite and in range, sigmas NaN (unknown) or finite and >= 0.
bool is_valid(const GpsFix& fix);
// speed finite and >= 0, track finite, vertical speed finite or NaN (unknown).
bool is_valid(const GpsVelocity& vel);
// every field flagged as present finite, orientation of unit norm (+-10 %),
// sigma NaN (unknown) or finite and > 0, and at least one field present.
bool is_valid(const ImuSample& imu);

}  // namespace ugv::estimation
