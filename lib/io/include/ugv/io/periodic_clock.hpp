// Filtered arrival times for messages a device sends on its own fixed period: the LMS's
// scan telegrams (one per scan of the mirror), a CANopen drive's event-timer TPDOs.
//
// The host sees each message some time after the device sent it: scheduling, a USB
// adapter's latency timer, or a process that was not scheduled for 50 ms and then reads
// several messages in one chunk. Those delays went straight into the stamps, and at a
// nodding servo's 1 rad/s every 10 ms of delay tilts a laser scan by 0.01 rad: 5 cm of
// height at 5 m.
//
// The messages carry no time, so a message's device time is its count times the nominal
// period. The count advances by one per message and one more per message the caller knows
// it lost (a CRC error): not by the time between arrivals, because after a stall a late
// message cannot be told from a lost one by its arrival. A device that sends only every n-th
// period (an LMS on a line too slow for every scan) is given n. DeviceClockFilter fits the
// lower envelope of the arrivals against that device time (its drift term takes up a clock
// off its nominal rate, e.g. a mirror not quite at 75 Hz) and never returns a time later than
// the arrival.
//
// A count slips when a message vanishes unnoticed. Then every later arrival is half a period
// or more after the line: after kLateBeforeRestart such messages in a row the clock starts
// again. A count too far shows at once (an arrival half a period before the line) and
// restarts the filter. Both count in restarts().
#pragma once

#include <cstdint>

#include "ugv/io/device_clock_filter.hpp"

namespace ugv::io {

class PeriodicClock
{
public:
    static constexpr int kLateBeforeRestart = 8;

    // restarts_so_far: carried over from the clock of an earlier stream, for the counter.
    explicit PeriodicClock(double period_s, int periods_per_message = 1, uint64_t restarts_so_far = 0);

    // arrival_utime: when the message (its last byte) arrived; lost_since_last: messages known
    // lost since the last one (a decoder's CRC errors). Returns the filtered time of that
    // arrival: no later than arrival_utime.
    int64_t update(int64_t arrival_utime, int lost_since_last = 0);
    // The same for a message read some unknown time after it arrived (read_utime: a batched
    // read on a timer found it waiting in the port's buffer): it is counted, and stamped on
    // the line fitted to the promptly read ones, no later than read_utime. Its read time
    // moves neither the line nor the slip detection, which see only update()'s arrivals: a
    // caller that reads late must still read some messages promptly, at least a few per
    // half-second block (ugv-servo's wake windows). The first message of a stream is taken
    // as update() takes it.
    int64_t update_read_late(int64_t read_utime, int lost_since_last = 0);
    void reset();
    uint64_t restarts() const { return slips_ + filter_.restarts(); }

private:
    // The device time of the next message: one message, plus those known lost, further on.
    double advance(int lost_since_last);

    double period_s_;
    int periods_per_message_;
    DeviceClockFilter filter_;
    bool started_ = false;
    int64_t count_ = 0;
    int late_in_a_row_ = 0;
    uint64_t slips_ = 0;
};

}  // namespace ugv::io
