// Which interlacing order fits a nodding laser's data. An interlaced scan (LMS 2xx at 0.5 or
// 0.25 deg) measures neighbouring beams one mirror turn apart; while the laser nods, their
// tilts differ. Assembled with the right beam times, smooth ground comes out smooth; with
// the wrong order every other beam gets another beam's tilt, and the heights zig-zag between
// neighbours. So each candidate order re-times the scans (keeping each scan's last measured
// beam where it was published), assembles them, and scores the zig-zag: the RMS of the
// second difference z[i] - (z[i-1] + z[i+1]) / 2 over neighbouring valid beams (larger ones
// are edges, not zig-zag, and left out). The order with the least zig-zag fits.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <string>
#include <vector>

#include "ugv/nodscan/scan_assembler.hpp"
#include "ugv/nodscan/servo_history.hpp"

namespace ugv::nodscan {

struct InterlaceConfig
{
    // The mount changes no candidate's score by more than its effect on neighbours' heights
    // (sub-millimetre for centimetres of offset), so the default one serves for detection.
    AssemblerConfig assembler;
    double mirror_period_s = 1.0 / 75.0;  // one sweep, when a scan does not carry its own
    double degrees_per_sweep = 1.0;       // beam spacing of one sweep (sweeps = this / resolution)
    double max_range_m = 40.0;            // beams further away are left out
    double max_second_difference_m = 0.3; // larger: an edge, left out
};

struct OrderScore
{
    std::string name;              // "as published", or the order: "01", "10", "2031", ...
    double zigzag_rms_m = 0.0;     // RMS of the neighbours' second difference in height
    uint64_t triples = 0;          // neighbour triples scored
};

struct InterlaceResult
{
    std::vector<OrderScore> candidates;  // [0] the scans' own timing, then every order
    int best = -1;                       // the order with the least zig-zag (>= 1), -1 when none scored
    int runner_up = -1;
    uint64_t scans = 0;                  // scans scored
    uint64_t scans_skipped = 0;          // another sweep count than the first scan's, or no tilt
    // The runner-up's zig-zag over the best's (>= 1; 1 when they tie).
    double margin() const;
};

class InterlaceDetector
{
public:
    explicit InterlaceDetector(InterlaceConfig config = {});

    // Servo tilt samples and scans, each in time order (as in a log). A scan is scored once
    // a servo sample after its last beam has arrived (or at finish()).
    void add_servo(const TiltSample& sample);
    void add_scan(const ScanView& scan);
    InterlaceResult finish();

private:
    struct Pending
    {
        ScanView view;
        std::vector<float> ranges;
        int64_t last_beam_utime = 0;
    };
    void score(const Pending& p);
    void score_ready(bool all);
    void start_candidates(int sweeps);

    InterlaceConfig config_;
    ServoHistory servo_;
    ScanAssembler assembler_;
    std::deque<Pending> pending_;
    int sweeps_ = 0;  // of the first scan; 0 before it
    std::vector<std::array<int8_t, ScanView::kMaxSweeps>> orders_;
    std::vector<double> sum_sq_;
    InterlaceResult result_;
    PointCloud cloud_;
    std::vector<double> z_;
    std::vector<uint8_t> has_z_;
};

}  // namespace ugv::nodscan
