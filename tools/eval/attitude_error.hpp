// Attitude against the simulator's truth: roll, pitch and yaw error statistics of a source
// (the IMU's own output, the pose), split by what the vehicle was doing: standing, driving
// straight, turning. No I/O: ugv-eval attitude feeds it from a log.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace ugv::eval {

struct TruthSample
{
    int64_t utime;
    double roll_rad, pitch_rad, yaw_rad;  // the project's convention (body FLU in ENU)
    double speed_mps;
};

struct AttitudeRules
{
    double turn_rate_radps = 1.0 * 3.14159265358979323846 / 180.0;  // |yaw rate| above: turning
    double standing_speed_mps = 0.1;                                  // below (and not turning): standing
    double max_truth_gap_s = 0.1;  // a sample between truth samples further apart is not scored
};

enum class Motion { standing, straight, turning };
inline constexpr const char* kMotionNames[] = {"standing", "straight", "turning"};

// The truth, in time order; interpolated, with the yaw rate over +/- 0.1 s.
class TruthTrack
{
public:
    explicit TruthTrack(std::vector<TruthSample> samples);  // sorts them by time
    struct At
    {
        double roll_rad, pitch_rad, yaw_rad, yaw_rate_radps, speed_mps;
    };
    std::optional<At> at(int64_t utime, double max_gap_s) const;

private:
    std::vector<TruthSample> samples_;
    std::optional<double> yaw_at(int64_t utime, double max_gap_s) const;
};

struct ErrorStats
{
    uint64_t samples = 0;
    double roll_sum2 = 0, pitch_sum2 = 0, yaw_sum2 = 0;  // rad^2
    double roll_max = 0, pitch_max = 0, yaw_max = 0;     // |error|, rad
    void add(double roll_err, double pitch_err, double yaw_err);
    double rms(double sum2) const;
};

// One source's errors by motion and over all.
class AttitudeErrors
{
public:
    AttitudeErrors(const TruthTrack& truth, const AttitudeRules& rules) : truth_(truth), rules_(rules) {}
    // false: no truth around that time (not scored).
    bool add(int64_t utime, double roll_rad, double pitch_rad, double yaw_rad);
    const ErrorStats& of(Motion m) const { return by_motion_[static_cast<int>(m)]; }
    const ErrorStats& all() const { return all_; }
    uint64_t unscored() const { return unscored_; }

private:
    const TruthTrack& truth_;
    AttitudeRules rules_;
    ErrorStats by_motion_[3];
    ErrorStats all_;
    uint64_t unscored_ = 0;
};

// One JSON line: {"source": ..., "motion": ..., "samples": N, "roll_rms_deg": ..., ...}.
std::string json_line(const std::string& source, const std::string& motion, const ErrorStats& s);

}  // namespace ugv::eval
