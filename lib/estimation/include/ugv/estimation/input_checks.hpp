// Which inputs the estimator refuses outright: non-finite or out-of-range values and
// impossible time stamps. Everything refused here is counted as non_finite.
#pragma once

#include "ugv/estimation/inputs.hpp"

namespace ugv::estimation {

// lat/lon/height finite and in range, utime > 0, sigmas NaN (unknown) or finite and >= 0.
bool is_valid(const GpsFix& fix);
// utime > 0, speed finite and >= 0, track finite, vertical speed finite or NaN (unknown).
bool is_valid(const GpsVelocity& vel);
// utime > 0, every field flagged as present finite, orientation of unit norm (+-10 %),
// sigma NaN (unknown) or finite and > 0, and at least one field present.
bool is_valid(const ImuSample& imu);

}  // namespace ugv::estimation
