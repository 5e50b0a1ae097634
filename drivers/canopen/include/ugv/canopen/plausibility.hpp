// The TPDO plausibility check for links without a checksum (slcan's ASCII lines): a bit
// error there can turn a position TPDO into another well-formed one. A reading is taken at
// once only when the frame just before it was taken and nothing was lost between, and it
// is within one drive period's travel of that frame (2 x the velocity cap x the period,
// plus a slack) with the same CiA 402 state. Anything else (the first reading, one after a
// lost or refused frame, a state change) waits for the next frame to confirm it the same
// way, and must then also lie within the travel at the cap since the last reading taken
// (n periods x cap x period + slack: the same bit flipped in two frames in a row agrees with
// itself); one never confirmed is dropped and counted. The bound to a neighbour never grows
// with a gap, so a corrupted reading after a burst of losses gets no more room than any.
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

    // travel_rad: how far the axis can move in one drive period (TPDO or SYNC period) at its
    // velocity cap; slack_rad: quantisation and overshoot. Neighbouring frames may differ by
    // twice the travel (a frame that vanished unnoticed between them) plus the slack.
    TpdoPlausibility(double travel_rad, double slack_rad)
        : travel_rad_(travel_rad), slack_rad_(slack_rad), max_step_rad_(2.0 * travel_rad + slack_rad)
    {
    }

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

    double travel_rad_;
    double slack_rad_;
    double max_step_rad_;
    std::optional<Reading> previous_;  // the frame before, taken or held
    bool previous_taken_ = false;
    bool gap_ = false;
    std::optional<Reading> taken_;  // the last reading taken
    int since_taken_ = 0;           // frames (and lost lines) since
    uint64_t dropped_ = 0;
};

}  // namespace ugv::canopen
