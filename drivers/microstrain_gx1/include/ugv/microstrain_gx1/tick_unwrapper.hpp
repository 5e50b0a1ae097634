// The 3DM-GX1 timer is a u16 that wraps (every 65536 ticks: 7.2 min at 6.5536 ms per tick).
// Unwrapping assumes consecutive readings are less than one wrap apart, which holds while
// frames flow; after a silence longer than a wrap the session resets the unwrapper.
#pragma once

#include <cstdint>

namespace ugv::microstrain_gx1 {

class TickUnwrapper
{
public:
    // The unwrapped count; the first reading after construction or reset() starts at its raw value.
    int64_t unwrap(uint16_t ticks)
    {
        if (!started_) {
            started_ = true;
            total_ = ticks;
        } else {
            total_ += static_cast<uint16_t>(ticks - last_);  // forward distance modulo 2^16
        }
        last_ = ticks;
        return total_;
    }
    void reset() { started_ = false; }

private:
    bool started_ = false;
    uint16_t last_ = 0;
    int64_t total_ = 0;
};

}  // namespace ugv::microstrain_gx1
