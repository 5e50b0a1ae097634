// The report's section 7 experiment, simulated: a nodding laser 0.87 m above a flat floor
// scans it in lines 10 cm apart; each scan's points are fused with an orientation that
// carries the IMU's error (one draw per scan, Gaussian, sigma = the IMU's stated accuracy),
// with classical (eq. 21-22) or variance-weighted (eq. 23, 32) statistics, the weights
// from eq. 19 with de = that accuracy. Tables 3 and 4 are the mean height of the map and
// the spread of its cells.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "ugv/terrain/evaluation.hpp"

namespace ugv::terrain {

struct FloorStudyCase
{
    std::string name;             // "no IMU", "3DM-G static", "3DM-G", "3DM-GX1"
    double noise_sigma_deg;       // orientation error added per scan (roll, pitch, yaw)
    double model_sigma_deg;       // de of eq. 19 given to the map (the pose covariance)
};

struct FloorStudyOptions
{
    double laser_height_m = 0.87;
    double line_spacing_m = 0.10;   // uniform scan density
    double first_line_m = 1.0;
    double last_line_m = 20.0;
    double beam_step_deg = 0.5;     // 361 beams over 180 deg
    double range_sigma_m = 0.01;    // SICK range noise
    double max_range_m = 30.0;
    uint64_t seed = 1;
    int trials = 5;                 // averaged
    bool spread = false;            // section 3.5 off: Tables 3-4 compare the statistics alone
    // Driving: the vehicle moves forward at speed_mps while the laser nods nods times over
    // the lines, so each patch is scanned again from nearer (the report's continuous motion).
    double speed_mps = 0.0;
    int nods = 1;
    // A cell "seen from several ranges": the longest range of its points is at least this
    // many times the shortest. Only there can weighting by eq. 19 differ from the plain mean.
    double several_ranges_ratio = 2.0;
};

struct FloorStudyResult
{
    FloorStudyCase scenario;
    StatisticsKind statistics;
    MapMetrics metrics;             // averaged over the trials
    MapMetrics several_ranges;      // the same over the cells seen from several ranges only
    double bias_standard_error_m = 0.0;  // of metrics.bias_m, from the spread between trials
};

// The cases of Tables 3 and 4.
std::vector<FloorStudyCase> report_cases();
// One case with one statistics kind, averaged over options.trials.
FloorStudyResult run_floor_study(const FloorStudyCase& scenario, StatisticsKind statistics,
                                 const FloorStudyOptions& options);

}  // namespace ugv::terrain
