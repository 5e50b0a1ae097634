// ugv-eval interlace LOG: which interlacing order of the laser's sweeps fits a log of a
// nodding scan (LMS_SCAN + SERVO_STATE), by the neighbour zig-zag of the assembled heights
// (lib/nodscan interlace_order.hpp, docs/lms.md "Beam timing"). A thin adapter: reads the
// log, hands the messages to the detector, prints its scores and verdict.
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace ugv::eval {

class InterlaceCommand
{
public:
    explicit InterlaceCommand(CLI::App& app);
    InterlaceCommand(const InterlaceCommand&) = delete;  // CLI11 holds references to the members
    InterlaceCommand& operator=(const InterlaceCommand&) = delete;
    bool chosen() const { return sub_->parsed(); }
    // Exit status: 0 when one order fits clearly (or the scans' own timing beats every
    // interlaced order by --min-margin: not interlaced), 1 when the log cannot tell (no
    // nodding scans, or the best two orders within --min-margin), 2 when the log cannot be read.
    int run() const;

private:
    CLI::App* sub_;
    std::string log_, scan_channel_ = "LMS_SCAN", servo_channel_ = "SERVO_STATE", sensor_id_;
    double max_range_m_ = 40.0;
    double min_margin_ = 1.2;
    bool json_ = false;
};

}  // namespace ugv::eval
