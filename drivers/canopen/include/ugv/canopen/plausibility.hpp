// The TPDO plausibility check for links without a checksum (slcan's ASCII lines): a bit
// error there can turn a position TPDO into another well-formed one. A reading is taken at
// once only when the frame just before it was taken and nothing was lost between, and it
// is within one drive period's travel of that frame (2 x the velocity cap x the period,
// plus a slack) with the same CiA 402 state. Anything else (the first reading, one after a
// lost or refused frame, a state change) waits for the next frame to confirm it within one
// period, and the pair must lie within the travel possible since the last reading taken (n
// periods); one never confirmed is dropped and counted. No reading is taken on its own after
// a gap, so a corrupted one after a burst of losses needs a second frame corrupted the same.
#pragma once

#include <cstdint>
#include <optional>

#include "ugv/canopen/cia402.hpp"

namespace ugv::canopen {

class TpdoPlausibility
{
public:
    struct Reading
    {
        cia402::State state = cia402::State::unknown;
        double angle_rad = 0.0;
    };

    // max_step_rad: how far the axis can move in one drive period (TPDO or SYNC period).
    explicit TpdoPlausibility(double max_step_rad) : max_step_rad_(max_step_rad) {}

    // A frame that may have been a position TPDO was lost (a malformed line).
    void note_lost()
    {
        gap_ = true;
        ++since_taken_;
    }
    // True when the reading may be used now.
    bool check(const Reading& r);
    void reset();
    uint64_t dropped() const { return dropped_; }
    double max_step_rad() const { return max_step_rad_; }

private:
    bool agree(const Reading& a, const Reading& b) const;

    double max_step_rad_;
    std::optional<Reading> previous_;  // the frame before, taken or held
    bool previous_taken_ = false;
    bool gap_ = false;
    std::optional<Reading> taken_;  // the last reading taken
    int since_taken_ = 0;           // frames (and lost lines) since
    uint64_t dropped_ = 0;
};

}  // namespace ugv::canopen
