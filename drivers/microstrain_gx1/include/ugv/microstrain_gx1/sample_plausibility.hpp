// Catches the samples whose corruption the GX1's checksum let through.
//
// The checksum is a 16-bit sum of the frame's words: two flips of the same bit weight in
// opposite directions cancel, so at 1e-2 bit errors per byte about 6e-4 of the frames arrive
// damaged but valid (ugv-imu once published roll 55 deg, accel z 30 m/s^2 from one). Such a
// sample disagrees with its neighbours by more than a body can move in one frame period:
//   timer     steps forward by 0 < step <= 1 s (a damaged timer word would restart the clock);
//   attitude  each Euler angle within (1.5 x the larger measured rate + 0.2 rad/s) x dt + 0.35 rad
//             (20 deg: the angles' own noise, up to a few degrees per sample, must pass);
//   rate      within 50 rad/s^2 x dt + 0.5 rad/s per axis;
//   accel     within 300 m/s^3 x dt + 20 m/s^2 per axis;
//   mag       within 2 gauss/s x dt + 0.2 gauss per axis.
// A sample that agrees with the last one taken is taken at once (no added latency). One that
// does not is held: if the next agrees with the last taken, the held one was damaged and is
// dropped (counted); if the next agrees with the held one, the change was real (a hard knock,
// a restarted unit) and the next is taken. The very first sample waits for the second.
#pragma once

#include <cstdint>
#include <optional>

#include "ugv/microstrain_gx1/scaling.hpp"

namespace ugv::microstrain_gx1 {

class SamplePlausibility
{
public:
    // tick_period_s: seconds per timer tick (EEPROM timing). True: publish this sample.
    bool check(const DeviceSample& s, double tick_period_s);
    void reset();
    uint64_t implausible() const { return implausible_; }

private:
    bool agree(const DeviceSample& earlier, const DeviceSample& later, double tick_period_s) const;

    std::optional<DeviceSample> last_taken_;
    std::optional<DeviceSample> previous_;  // the last one received, taken or not
    bool holding_ = false;                  // previous_ was not taken
    uint64_t implausible_ = 0;
};

}  // namespace ugv::microstrain_gx1
