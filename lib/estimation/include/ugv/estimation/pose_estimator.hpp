// The pose estimator: GPS fixes, GPS velocities and IMU samples in (any order), poses with
// covariance out on data time.
//
// Time: everything is driven by the inputs' utime, never by a clock, so the same inputs in the
// same order give bit-identical poses. Inputs wait in a buffer ordered by utime until the
// newest input seen is buffer_us newer than them (0: applied as they come); then they are
// applied in time order. An input older than the last one applied is applied at its own time
// from the history: the state just before it is restored from a ring of the last
// history_size states and the inputs after it are applied again, so a late GPS measurement
// gives the same state as one delivered in order. Poses already produced are not revised.
// An input older than the history is refused and counted (late); so is one stamped more than
// max_ahead_us ahead of the newest input taken, unless the next input is as well (a gap in
// every input, not one bad stamp): one such input would otherwise move the filter ahead.
//
// Poses: with PoseTimes::grid at every multiple of the output period (utime % period == 0)
// that the filter passes, by predicting to exactly that time; with PoseTimes::imu at the time
// of the first IMU sample applied in each period (the newest state, right after the sample).
// A gap between inputs longer than gps_reset_after_us is not predicted across (one step per
// period of it, with poses nobody wants): the filter restarts from the next fix, so the work
// per input is bounded whatever the stamps say.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "ugv/estimation/error_state_filter.hpp"
#include "ugv/estimation/inputs.hpp"
#include "ugv/estimation/local_frame.hpp"

namespace ugv::estimation {

enum class PoseTimes : int8_t { grid, imu };

struct EstimatorConfig
{
    // Datum of the local ENU frame; std::nullopt = the first fix of datum_min_quality.
    std::optional<Datum> datum;
    FixQuality datum_min_quality = FixQuality::single;
    FixQuality min_fix_quality = FixQuality::single;  // fixes below this are not used

    int64_t output_period_us = 100'000;  // 10 Hz
    int64_t buffer_us = 150'000;         // reorder window
    PoseTimes pose_times = PoseTimes::grid;
    // States and inputs kept to apply a late input at its own time (0: late inputs are refused).
    std::size_t history_size = 100;
    int64_t max_ahead_us = 500'000;  // an input further ahead of the newest taken is refused

    ProcessNoise process;
    double imu_orientation_sigma_rad = 0.035;   // when the sample does not carry one
    // The IMU's roll and pitch come from its own filter, which takes the vehicle's acceleration
    // for gravity: its tilt error is correlated over that filter's time constant and grows
    // with the acceleration. Each sample's tilt variance is (sigma^2 + (accel_factor a / g)^2)
    // x time_constant / (time since the last sample), a = the peak horizontal acceleration
    // (GPS velocity and body rate) decaying with the time constant: one time constant of
    // samples weighs as one independent measurement. 0 = samples independent, no inflation.
    double imu_tilt_time_constant_s = 10.0;
    double imu_tilt_accel_factor = 1.0;
    // The IMU's yaw (compass) error is correlated too: the deviation changes with the heading
    // and the false tilt turns into heading error. > 0: each sample's yaw variance is sigma^2
    // x time_constant / (time since the last sample). 0 (default) = yaw samples independent:
    // the honest yaw sigma standing still widens the terrain map's spread (docs/pose.md "Yaw").
    double imu_yaw_time_constant_s = 0.0;
    double initial_gyro_bias_sigma_rps = 0.0087;  // 0.5 deg/s
    double gps_default_sigma_m = 5.0;           // when the fix does not carry sigmas
    double gps_min_sigma_m = 0.01;              // floor on reported sigmas
    double gps_velocity_sigma_mps = 0.1;        // 1-sigma per ENU axis
    double course_min_speed_mps = 1.0;          // course over ground used above this speed
    double course_sigma_rad = 0.05;             // sideslip and antenna misalignment
    Eigen::Vector3d gps_antenna_body_m = Eigen::Vector3d::Zero();  // lever arm of the antenna

    double gate_position_chi2 = 16.27;     // 3 dof, p = 0.999
    double gate_velocity_chi2 = 16.27;
    double gate_orientation_chi2 = 16.27;
    double gate_course_chi2 = 10.83;       // 1 dof, p = 0.999

    int64_t gps_timeout_us = 1'000'000;     // no fix used for this long: outage, DEGRADED
    int64_t imu_timeout_us = 500'000;       // no IMU for this long: constant-velocity prediction
    int64_t gps_reset_after_us = 10'000'000;  // fixes rejected this long: re-anchor on the fix

    double initial_velocity_sigma_mps = 1.0;
    double initial_heading_sigma_rad = 0.5;  // true yaw before the course has been seen

    // Throws std::invalid_argument naming the first bad field.
    void validate() const;
};

enum class PoseStatus : int8_t { initializing = 0, ok = 1, degraded = 2, fault = 3 };

struct PoseEstimate
{
    int64_t utime = 0;
    PoseStatus status = PoseStatus::initializing;
    Eigen::Vector3d position = Eigen::Vector3d::Zero();  // m, ENU of the datum
    Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // m/s, ENU
    Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  // body -> ENU
    double roll = 0.0, pitch = 0.0, yaw = 0.0;  // rad (Z-Y-X); yaw 0 = east, CCW
    Eigen::Vector3d rotation_rate = Eigen::Vector3d::Zero();  // rad/s body, last IMU sample
    Eigen::Matrix3d position_covariance = Eigen::Matrix3d::Zero();     // m^2 (E, N, U)
    Eigen::Matrix3d velocity_covariance = Eigen::Matrix3d::Zero();     // (m/s)^2
    Eigen::Matrix3d orientation_covariance = Eigen::Matrix3d::Zero();  // rad^2 (roll, pitch, yaw)
    Eigen::Matrix3d attitude_error_covariance = Eigen::Matrix3d::Zero();  // rad^2, world rotation vector
    // The filter's whole error-state covariance (dp, dv, dtheta, d offset; see
    // ErrorStateFilter), for consumers that need the cross terms.
    ErrorStateFilter::Covariance error_covariance = ErrorStateFilter::Covariance::Zero();
    double heading_offset = 0.0;        // rad, IMU yaw minus true yaw
    double heading_offset_sigma = 0.0;  // rad
    Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();  // rad/s, body
    double imu_tilt_sigma = 0.0;  // rad, the last IMU tilt sample's sigma before the time-constant weighting
    bool heading_observed = false;      // GPS course has aligned the heading
    bool gps_outage = false;
    Datum datum;
};

struct EstimatorCounters
{
    int64_t gps_used = 0;
    int64_t gps_rejected = 0;       // failed the Mahalanobis gate
    int64_t gps_low_quality = 0;    // below min_fix_quality
    int64_t gps_resets = 0;         // re-anchored after gps_reset_after_us of rejections
    int64_t velocity_used = 0;
    int64_t velocity_rejected = 0;
    int64_t course_used = 0;
    int64_t course_rejected = 0;
    int64_t imu_used = 0;
    int64_t imu_rejected = 0;       // orientation failed the gate
    int64_t late = 0;               // older than the history (or the last applied, without one)
    int64_t reordered = 0;          // arrived out of order: buffered, or applied from the history
    int64_t ahead = 0;              // stamped more than max_ahead_us after the newest input taken
    int64_t duplicates = 0;         // same kind and utime as one buffered or last applied: dropped
    int64_t outages = 0;            // GPS outages started
    int64_t non_finite = 0;         // refused by input_checks
    int64_t filter_resets = 0;      // the filter went non-finite and restarted
    int64_t input_gaps = 0;         // no input for > gps_reset_after_us: restarted from the next fix
    int64_t poses = 0;

    template <class F>
    void visit(F&& f) const
    {
        f("poses", poses);
        f("gps_used", gps_used);
        f("gps_rejected", gps_rejected);
        f("gps_low_quality", gps_low_quality);
        f("gps_resets", gps_resets);
        f("velocity_used", velocity_used);
        f("velocity_rejected", velocity_rejected);
        f("course_used", course_used);
        f("course_rejected", course_rejected);
        f("imu_used", imu_used);
        f("imu_rejected", imu_rejected);
        f("late", late);
        f("reordered", reordered);
        f("ahead", ahead);
        f("outages", outages);
        f("non_finite", non_finite);
        f("filter_resets", filter_resets);
        f("input_gaps", input_gaps);
        f("duplicates", duplicates);
    }
};

class PoseEstimator
{
public:
    // Throws std::invalid_argument for an invalid config.
    explicit PoseEstimator(EstimatorConfig config);

    void add(const GpsFix& fix);
    void add(const GpsVelocity& velocity);
    void add(const ImuSample& sample);
    // Applies everything still buffered (end of a log).
    void flush();

    // The poses produced since the last call, oldest first.
    std::vector<PoseEstimate> take_poses();

    const EstimatorCounters& counters() const { return counters_; }
    bool initialized() const { return c_.initialized; }
    const std::optional<LocalFrame>& frame() const { return frame_; }
    const ErrorStateFilter& filter() const { return c_.filter; }
    const EstimatorConfig& config() const { return config_; }

private:
    struct Event
    {
        int64_t utime;
        uint64_t arrival;
        std::variant<ImuSample, GpsFix, GpsVelocity> data;
    };

    // Everything applying an input changes: restored from the history for a late input.
    struct Core
    {
        ErrorStateFilter filter;
        int64_t applied_utime = 0;  // utime of the last applied event
        std::array<int64_t, 3> applied_utime_by_kind{};  // the same, per Event::data index
        int64_t filter_utime = 0;   // time the filter state is valid at
        int64_t next_output_utime = 0;
        bool initialized = false;
        bool heading_observed = false;
        std::optional<ImuSample> last_imu;
        std::optional<ImuSample> last_orientation;
        int64_t last_fix_used_utime = 0;
        std::optional<GpsVelocity> last_velocity;  // the start of the acceleration's baseline
        double along_track_accel = 0.0;  // m/s^2, from GPS velocities >= 1 s apart
        double accel_envelope = 0.0;     // m/s^2, peak horizontal acceleration, decaying
        double imu_tilt_sigma = 0.0;     // rad, of the last tilt sample (before weighting)
    };
    struct Applied
    {
        Event input;
        Core after;  // the state once input was applied
    };

    bool ahead_of_newest(int64_t utime);
    void enqueue(int64_t utime, std::variant<ImuSample, GpsFix, GpsVelocity> data);
    void apply_late(Event e);
    void release(int64_t up_to_utime);
    void apply(const Event& e);
    void advance_to(int64_t utime);
    void predict_to(int64_t utime);
    void emit(int64_t utime);
    void apply_imu(const ImuSample& s);
    void apply_fix(const GpsFix& f);
    void apply_velocity(const GpsVelocity& v);
    void initialize(const GpsFix& f, const Eigen::Vector3d& antenna_enu, const Eigen::Matrix3d& cov);
    Eigen::Matrix3d fix_covariance(const GpsFix& f) const;
    double imu_sigma(const ImuSample& s) const;
    Eigen::Vector3d imu_rate() const;
    Eigen::Matrix3d imu_orientation_covariance(const ImuSample& s);

    EstimatorConfig config_;
    Core c_;
    std::optional<LocalFrame> frame_;  // never rewound: the datum stays what poses carried
    EstimatorCounters counters_;
    std::deque<Event> buffer_;
    std::deque<Applied> history_;  // oldest first, at most history_size
    uint64_t arrivals_ = 0;
    int64_t newest_utime_ = 0;
    bool refused_ahead_ = false;   // the last input was refused as ahead of the newest
    int64_t emitted_utime_ = 0;    // the newest pose produced: none at or before it again
    bool in_outage_ = false;
    std::vector<PoseEstimate> poses_;
};

}  // namespace ugv::estimation
