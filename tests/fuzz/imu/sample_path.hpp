// What the GX1 session does with each verified frame (Session::emit): scale it, unwrap the
// device timer, stamp it through the clock filter and convert it to body FLU / ENU, with the
// checks both IMU fuzz targets make on the result.
#pragma once

#include <cstdint>

#include "ugv/io/device_clock_filter.hpp"
#include "ugv/microstrain_gx1/frame_parser.hpp"
#include "ugv/microstrain_gx1/orientation.hpp"
#include "ugv/microstrain_gx1/tick_unwrapper.hpp"

namespace ugv::fuzz {

class SamplePath
{
public:
    // Checks:
    //  - the frame has the word count of its command;
    //  - every scaled value and every converted value is finite;
    //  - an orientation is a unit quaternion with w >= 0 and yaw in [-pi, pi];
    //  - the unwrapped timer never runs backwards;
    //  - the filtered stamp is never later than the frame's arrival (the filter's promise).
    void on_frame(const microstrain_gx1::Frame& frame);

private:
    microstrain_gx1::GainScales gains_;
    microstrain_gx1::FrameConverter converter_;
    microstrain_gx1::TickUnwrapper ticks_;
    io::DeviceClockFilter clock_;
    int64_t last_ticks_ = INT64_MIN;
};

}  // namespace ugv::fuzz
