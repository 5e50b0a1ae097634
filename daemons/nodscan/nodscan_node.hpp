// The adapter between the bus and the scan assembler: keeps the servo history, holds each
// scan until a servo sample at or after its last beam arrived (or until it waited
// max_wait_us of message time, then uses what there is), and emits point_cloud_t.
// Driven by message time only, so a replayed log gives the same output at any speed.
#pragma once

#include <cstdint>
#include <deque>
#include <functional>

#include "nodscan_config.hpp"
#include "ugv/daemon/daemon.hpp"
#include "ugv/laser_scan_t.hpp"
#include "ugv/nodscan/scan_assembler.hpp"
#include "ugv/point_cloud_t.hpp"
#include "ugv/servo_state_t.hpp"

namespace ugv::nodscan_daemon {

struct NodscanCounters
{
    uint64_t scans_in = 0;
    uint64_t scans_out = 0;
    uint64_t points_out = 0;
    uint64_t dropped_invalid = 0;     // beams without a valid range
    uint64_t dropped_no_angle = 0;    // beams without a servo angle
    uint64_t scans_without_servo = 0; // scans that got no angle at all (not published)
    uint64_t scans_overflow = 0;      // pending scans pushed out by newer ones
    uint64_t servo_rejected = 0;      // out of order or non-finite servo samples
    uint64_t scans_other_sensor = 0;
    uint64_t scans_bad_timing = 0;    // beam spacing non-finite, negative, or a scan over 1 s

    template <class F>
    void visit(F&& f) const
    {
        f("scans_in", scans_in);
        f("scans_out", scans_out);
        f("points_out", points_out);
        f("dropped_invalid", dropped_invalid);
        f("dropped_no_angle", dropped_no_angle);
        f("scans_without_servo", scans_without_servo);
        f("scans_overflow", scans_overflow);
        f("servo_rejected", servo_rejected);
        f("scans_other_sensor", scans_other_sensor);
        f("scans_bad_timing", scans_bad_timing);
    }
};

class NodscanNode
{
public:
    using Publish = std::function<void(const point_cloud_t&)>;
    NodscanNode(const NodscanConfig& config, Publish publish);

    void on_servo(const servo_state_t& msg);
    void on_scan(const laser_scan_t& msg);
    // Live mode only: scans that waited longer than max_wait (in wall time since they
    // arrived, measured by the caller) are assembled with what there is.
    void flush_older_than(int64_t message_utime);
    // Assembles everything that is pending (end of a replay).
    void flush_all();

    const NodscanCounters& counters() const { return counters_; }

private:
    void process_ready();
    void assemble(const laser_scan_t& scan);

    NodscanConfig config_;
    Publish publish_;
    nodscan::ServoHistory servo_;
    nodscan::ScanAssembler assembler_;
    nodscan::PointCloud cloud_;
    std::deque<laser_scan_t> pending_;
    int64_t newest_message_utime_ = INT64_MIN;
    int64_t seq_ = 0;
    NodscanCounters counters_;
};

// The daemon: a NodscanNode on the bus until a stop signal, or the end of the --replay log.
int run(daemon::Daemon& d, const NodscanConfig& config);

}  // namespace ugv::nodscan_daemon
