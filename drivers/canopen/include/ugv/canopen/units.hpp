// Drive counts <-> radians at the output (the laser's tilt axis).
//   angle_rad = direction * (counts - zero_offset) * 2 pi / (counts_per_rev * gear_ratio)
// counts_per_rev is the encoder's counts per motor revolution (after quadrature), gear_ratio
// motor revolutions per output revolution, zero_offset the count at tilt 0 (laser level),
// direction +1 or -1 so that positive angles are nose down (servo_state_t convention).
#pragma once

#include <cstdint>

namespace ugv::canopen {

struct UnitConversion
{
    double counts_per_rev = 4096.0;
    double gear_ratio = 1.0;
    int64_t zero_offset = 0;  // counts
    int direction = 1;        // +1 or -1

    double counts_per_rad() const;
    double to_rad(int64_t counts) const;
    double to_rad_s(double counts_per_s) const;
    // Rounded to the nearest count, clamped to the int32 range of 0x607A.
    int32_t to_counts(double rad) const;
    // A speed or acceleration magnitude in counts/s (or counts/s^2), rounded, >= 0.
    uint32_t to_counts_rate(double rad_per_s) const;
};

}  // namespace ugv::canopen
