// Eq. 19-20: a laser point lies in a sphere of radius ds = sqrt(2 (r de)^2) around its
// measured position, r the range and de the orientation error; its variance is ds^2. The
// sensor's own part (range and encoder noise, from ugv-nodscan) adds to it.
#pragma once

namespace ugv::terrain {

// sensor_variance_m2: the sensor part; range_m: r; orientation_error_rad2: de^2.
inline float point_variance_m2(float sensor_variance_m2, float range_m, float orientation_error_rad2)
{
    return sensor_variance_m2 + 2.0f * range_m * range_m * orientation_error_rad2;
}

}  // namespace ugv::terrain
