#include "ugv/estimation/pose_estimator.hpp"

#include <algorithm>
#include <iterator>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "ugv/estimation/input_checks.hpp"
#include "ugv/geometry/rotation.hpp"

namespace ugv::estimation {

using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

// Longest single prediction step (s): keeps the linearised covariance step accurate when
// inputs are sparse (an IMU outage, a slow log).
constexpr double kMaxStepS = 0.05;
// Shortest interval between the GPS velocities the along-track acceleration is taken from.
constexpr int64_t kAccelBaselineUs = 1'000'000;

void require(bool ok, const char* field)
{
    if (!ok) {
        throw std::invalid_argument(std::string("estimator config: ") + field);
    }
}

bool positive(double x)
{
    return std::isfinite(x) && x > 0.0;
}

}  // namespace

void EstimatorConfig::validate() const
{
    require(output_period_us > 0, "output_period_us must be > 0");
    require(buffer_us >= 0, "buffer_us must be >= 0");
    require(history_size <= 100'000, "history_size must be <= 100000");
    require(max_ahead_us > 0 && max_ahead_us <= 3'600'000'000, "max_ahead_us must be in (0, 3600 s]");
    require(positive(process.accel) && positive(process.gyro) && positive(process.heading_offset),
            "process noise densities must be > 0");
    require(positive(imu_orientation_sigma_rad), "imu_orientation_sigma_rad must be > 0");
    require(positive(process.gyro_bias), "process.gyro_bias must be > 0");
    require(std::isfinite(imu_tilt_time_constant_s) && imu_tilt_time_constant_s >= 0.0,
            "imu_tilt_time_constant_s must be >= 0");
    require(std::isfinite(imu_tilt_accel_factor) && imu_tilt_accel_factor >= 0.0,
            "imu_tilt_accel_factor must be >= 0");
    require(std::isfinite(imu_yaw_time_constant_s) && imu_yaw_time_constant_s >= 0.0,
            "imu_yaw_time_constant_s must be >= 0");
    require(positive(initial_gyro_bias_sigma_rps), "initial_gyro_bias_sigma_rps must be > 0");
    require(positive(gps_default_sigma_m) && positive(gps_min_sigma_m), "GPS sigmas must be > 0");
    require(positive(gps_velocity_sigma_mps), "gps_velocity_sigma_mps must be > 0");
    require(std::isfinite(course_min_speed_mps) && course_min_speed_mps > 0.0, "course_min_speed_mps must be > 0");
    require(positive(course_sigma_rad), "course_sigma_rad must be > 0");
    require(gps_antenna_body_m.allFinite(), "gps_antenna_body_m must be finite");
    require(positive(gate_position_chi2) && positive(gate_velocity_chi2) && positive(gate_orientation_chi2) &&
                positive(gate_course_chi2),
            "gates must be > 0");
    require(gps_timeout_us > 0 && imu_timeout_us > 0 && gps_reset_after_us > 0, "timeouts must be > 0");
    require(positive(initial_velocity_sigma_mps) && positive(initial_heading_sigma_rad),
            "initial sigmas must be > 0");
    require(quality_rank(min_fix_quality) > 0 && quality_rank(datum_min_quality) > 0,
            "minimum fix qualities must be usable (single or better)");
}

PoseEstimator::PoseEstimator(EstimatorConfig config) : config_(std::move(config))
{
    config_.validate();
    if (config_.datum) {
        frame_.emplace(*config_.datum);
    }
}

void PoseEstimator::add(const GpsFix& fix)
{
    if (!is_valid(fix)) {
        ++counters_.non_finite;
        return;
    }
    enqueue(fix.utime, fix);
}

void PoseEstimator::add(const GpsVelocity& velocity)
{
    if (!is_valid(velocity)) {
        ++counters_.non_finite;
        return;
    }
    enqueue(velocity.utime, velocity);
}

void PoseEstimator::add(const ImuSample& sample)
{
    if (!is_valid(sample)) {
        ++counters_.non_finite;
        return;
    }
    enqueue(sample.utime, sample);
}

void PoseEstimator::flush()
{
    release(std::numeric_limits<int64_t>::max());
}

std::vector<PoseEstimate> PoseEstimator::take_poses()
{
    std::vector<PoseEstimate> out;
    out.swap(poses_);
    return out;
}

namespace {

// Ordered by (utime, kind, arrival): equal stamps apply IMU first, then fix, then velocity,
// whatever order they arrived in, so the result does not depend on transport.
template <class Event>
bool sorts_before(const Event& a, const Event& b)
{
    if (a.utime != b.utime) {
        return a.utime < b.utime;
    }
    if (a.data.index() != b.data.index()) {
        return a.data.index() < b.data.index();
    }
    return a.arrival < b.arrival;
}

}  // namespace

bool PoseEstimator::ahead_of_newest(int64_t utime)
{
    // Stamps are below 2^62 (input_checks) and max_ahead_us is bounded: no overflow.
    const bool ahead = newest_utime_ > 0 && utime > newest_utime_ + config_.max_ahead_us;
    if (!ahead) {
        refused_ahead_ = false;
        return false;
    }
    if (refused_ahead_) {
        // The input after one refused is ahead as well: every input says time moved on (the
        // inputs resume after a gap), so it is taken.
        refused_ahead_ = false;
        return false;
    }
    refused_ahead_ = true;
    ++counters_.ahead;
    return true;
}

void PoseEstimator::enqueue(int64_t utime, std::variant<ImuSample, GpsFix, GpsVelocity> data)
{
    if (ahead_of_newest(utime)) {
        return;
    }
    Event e{utime, arrivals_++, std::move(data)};
    if (utime < c_.applied_utime) {
        apply_late(std::move(e));
        return;
    }
    const auto pos = std::upper_bound(buffer_.begin(), buffer_.end(), e, sorts_before<Event>);
    // A second input of the same kind with the same measurement time is the same measurement
    // delivered twice (a re-sent or looped-back message): applying it again would count its
    // information twice and make the covariance overconfident.
    const bool buffered_twin =
        pos != buffer_.begin() && std::prev(pos)->utime == utime && std::prev(pos)->data.index() == e.data.index();
    if (buffered_twin || c_.applied_utime_by_kind[e.data.index()] == utime) {
        ++counters_.duplicates;
        return;
    }
    if (pos != buffer_.end()) {
        ++counters_.reordered;
    }
    buffer_.insert(pos, std::move(e));
    newest_utime_ = std::max(newest_utime_, utime);
    release(newest_utime_ - config_.buffer_us);
}

void PoseEstimator::apply_late(Event e)
{
    // The first kept input that comes after e: e goes just before it, on the state the
    // input before it left.
    const auto after = std::upper_bound(history_.begin(), history_.end(), e,
                                        [](const Event& x, const Applied& a) { return sorts_before(x, a.input); });
    if (after == history_.begin()) {
        ++counters_.late;  // no state from before it is kept
        return;
    }
    const Applied& prev = *std::prev(after);
    if (prev.input.utime == e.utime && prev.input.data.index() == e.data.index()) {
        ++counters_.duplicates;
        return;
    }
    ++counters_.reordered;
    const auto at = static_cast<std::size_t>(after - history_.begin());
    c_ = prev.after;
    apply(e);
    // The inputs after it were counted when they first came: applied again, not counted again
    // (poses are: only those not produced before come out).
    EstimatorCounters counted = counters_;
    history_.insert(history_.begin() + static_cast<std::ptrdiff_t>(at), Applied{std::move(e), c_});
    for (std::size_t i = at + 1; i < history_.size(); ++i) {
        apply(history_[i].input);
        history_[i].after = c_;
    }
    counted.poses = counters_.poses;
    counted.outages = counters_.outages;
    counters_ = counted;
    while (history_.size() > config_.history_size) {
        history_.pop_front();
    }
}

void PoseEstimator::release(int64_t up_to_utime)
{
    while (!buffer_.empty() && buffer_.front().utime <= up_to_utime) {
        Event e = std::move(buffer_.front());
        buffer_.pop_front();
        apply(e);
        if (config_.history_size > 0) {
            history_.push_back(Applied{std::move(e), c_});
            if (history_.size() > config_.history_size) {
                history_.pop_front();
            }
        }
    }
}

void PoseEstimator::apply(const Event& e)
{
    c_.applied_utime = e.utime;
    c_.applied_utime_by_kind[e.data.index()] = e.utime;
    if (c_.initialized && e.utime - c_.filter_utime > config_.gps_reset_after_us) {
        c_.initialized = false;
        c_.heading_observed = false;
        ++counters_.input_gaps;
    }
    if (c_.initialized) {
        advance_to(e.utime);
    }
    const auto* imu = std::get_if<ImuSample>(&e.data);
    if (imu) {
        apply_imu(*imu);
    } else if (const auto* fix = std::get_if<GpsFix>(&e.data)) {
        apply_fix(*fix);
    } else if (const auto* vel = std::get_if<GpsVelocity>(&e.data)) {
        apply_velocity(*vel);
    }
    // With the IMU silent, the GPS inputs carry the (dead-reckoned, DEGRADED) pose on.
    const bool imu_stale = !c_.last_imu || e.utime - c_.last_imu->utime > config_.imu_timeout_us;
    if (config_.pose_times == PoseTimes::imu && c_.initialized && (imu || imu_stale) &&
        e.utime >= c_.next_output_utime) {
        emit(e.utime);
        const int64_t period = config_.output_period_us;
        c_.next_output_utime = (e.utime / period + 1) * period;
    }
    if (c_.initialized && !c_.filter.healthy()) {
        // A non-finite state cannot recover by itself: start again from the next fix.
        c_.initialized = false;
        c_.heading_observed = false;
        ++counters_.filter_resets;
    }
}

void PoseEstimator::advance_to(int64_t utime)
{
    while (config_.pose_times == PoseTimes::grid && c_.next_output_utime <= utime) {
        predict_to(c_.next_output_utime);
        emit(c_.next_output_utime);
        c_.next_output_utime += config_.output_period_us;
    }
    predict_to(utime);
}

void PoseEstimator::predict_to(int64_t utime)
{
    if (utime <= c_.filter_utime) {
        return;
    }
    // The IMU sample last applied is held over the interval (zero-order hold). Without a
    // recent one the vehicle keeps its velocity and attitude.
    const Matrix3d r = c_.filter.state().attitude.toRotationMatrix();
    const Vector3d rate = imu_rate();
    Vector3d force = r.transpose() * Vector3d(0.0, 0.0, ErrorStateFilter::kGravity);
    if (c_.last_imu && c_.filter_utime - c_.last_imu->utime <= config_.imu_timeout_us && c_.last_imu->has_accel) {
        force = c_.last_imu->accel_mps2;
    }
    double remaining = static_cast<double>(utime - c_.filter_utime) * 1e-6;
    while (remaining > 0.0) {
        const double dt = std::min(remaining, kMaxStepS);
        c_.filter.predict(dt, rate, force, config_.process);
        remaining -= dt;
    }
    c_.filter_utime = utime;
}

void PoseEstimator::emit(int64_t utime)
{
    // Re-applying inputs after a late one passes times already published: a pose once out is
    // not revised (a consumer keeps poses in time order), the next one carries the correction.
    if (!c_.filter.healthy() || utime <= emitted_utime_) {
        return;
    }
    emitted_utime_ = utime;
    const bool outage = utime - c_.last_fix_used_utime > config_.gps_timeout_us;
    if (outage && !in_outage_) {
        ++counters_.outages;
    }
    in_outage_ = outage;
    const bool imu_stale = !c_.last_imu || utime - c_.last_imu->utime > config_.imu_timeout_us;

    const NominalState& s = c_.filter.state();
    const ErrorStateFilter::Covariance& P = c_.filter.covariance();
    PoseEstimate out;
    out.utime = utime;
    out.status = (outage || imu_stale || !c_.heading_observed) ? PoseStatus::degraded : PoseStatus::ok;
    out.position = s.position;
    out.velocity = s.velocity;
    out.orientation = s.attitude;
    const geometry::Euler e = geometry::euler_from_quaternion(s.attitude);
    out.roll = e.roll;
    out.pitch = e.pitch;
    out.yaw = e.yaw;
    if (c_.last_imu && c_.last_imu->has_rate && !imu_stale) {
        out.rotation_rate = c_.last_imu->rate_rps - s.gyro_bias;
    }
    out.position_covariance = P.block<3, 3>(ErrorStateFilter::kP, ErrorStateFilter::kP);
    out.velocity_covariance = P.block<3, 3>(ErrorStateFilter::kV, ErrorStateFilter::kV);
    out.attitude_error_covariance = P.block<3, 3>(ErrorStateFilter::kTheta, ErrorStateFilter::kTheta);
    const Matrix3d j = geometry::euler_jacobian_world(e);
    out.orientation_covariance = j * out.attitude_error_covariance * j.transpose();
    out.error_covariance = P;
    out.heading_offset = s.heading_offset;
    out.heading_offset_sigma = std::sqrt(P(ErrorStateFilter::kOffset, ErrorStateFilter::kOffset));
    out.gyro_bias = s.gyro_bias;
    out.imu_tilt_sigma = c_.imu_tilt_sigma;
    out.heading_observed = c_.heading_observed;
    out.gps_outage = outage;
    out.datum = frame_->datum();
    poses_.push_back(out);
    ++counters_.poses;
}

double PoseEstimator::imu_sigma(const ImuSample& s) const
{
    return std::isnan(s.orientation_sigma_rad) ? config_.imu_orientation_sigma_rad : s.orientation_sigma_rad;
}

Vector3d PoseEstimator::imu_rate() const
{
    // The filter removes its bias estimate from the rate: without a recent rate, handing it the
    // bias makes the vehicle hold its attitude.
    if (c_.last_imu && c_.last_imu->has_rate && c_.filter_utime - c_.last_imu->utime <= config_.imu_timeout_us) {
        return c_.last_imu->rate_rps;
    }
    return c_.filter.state().gyro_bias;
}

Matrix3d PoseEstimator::imu_orientation_covariance(const ImuSample& s)
{
    // The vehicle's horizontal acceleration from what does not depend on the tilt: the
    // along-track change of the GPS velocity and the centripetal yaw rate x speed. (The IMU's
    // own specific force would be circular: it is what the IMU's filter mistakes for tilt.)
    const double tau = config_.imu_tilt_time_constant_s;
    const double sigma = imu_sigma(s);
    const double dt =
        c_.last_orientation ? static_cast<double>(s.utime - c_.last_orientation->utime) * 1e-6 : 0.0;
    const double speed = c_.filter.state().velocity.head<2>().norm();
    const double yaw_rate = s.has_rate ? s.rate_rps.z() - c_.filter.state().gyro_bias.z() : 0.0;
    const double accel = std::hypot(c_.along_track_accel, yaw_rate * speed);
    const double decay = (tau > 0.0 && dt > 0.0) ? std::exp(-dt / tau) : 0.0;
    c_.accel_envelope = std::max(accel, c_.accel_envelope * decay);
    const double false_tilt = config_.imu_tilt_accel_factor * c_.accel_envelope / ErrorStateFilter::kGravity;
    double tilt_var = sigma * sigma + false_tilt * false_tilt;
    c_.imu_tilt_sigma = std::sqrt(tilt_var);
    // Samples closer than the time constant are not independent evidence.
    const auto correlated = [dt](double var, double time_constant_s) {
        return time_constant_s > 0.0 ? var * std::max(1.0, time_constant_s / std::max(dt, 1e-3)) : var;
    };
    tilt_var = correlated(tilt_var, tau);
    const double yaw_var = correlated(sigma * sigma, config_.imu_yaw_time_constant_s);
    // The residual is in the IMU's world frame (the true one turned by the heading offset about
    // Up): equal east and north variances make the turn irrelevant.
    return Eigen::Vector3d(tilt_var, tilt_var, yaw_var).asDiagonal();
}

Matrix3d PoseEstimator::fix_covariance(const GpsFix& f) const
{
    const auto sigma = [this](double reported) {
        return std::isnan(reported) ? config_.gps_default_sigma_m : std::max(reported, config_.gps_min_sigma_m);
    };
    const Vector3d s(sigma(f.sigma_east_m), sigma(f.sigma_north_m), sigma(f.sigma_up_m));
    return s.cwiseProduct(s).asDiagonal();
}

void PoseEstimator::apply_imu(const ImuSample& s)
{
    if (s.has_orientation) {
        if (c_.initialized) {
            const Matrix3d cov = imu_orientation_covariance(s);
            const UpdateResult r =
                c_.filter.update_imu_orientation(s.orientation.normalized(), cov, config_.gate_orientation_chi2);
            ++(r.applied ? counters_.imu_used : counters_.imu_rejected);
        }
        c_.last_orientation = s;
    }
    c_.last_imu = s;
}

void PoseEstimator::apply_fix(const GpsFix& f)
{
    if (quality_rank(f.quality) < quality_rank(config_.min_fix_quality)) {
        ++counters_.gps_low_quality;
        return;
    }
    if (!frame_) {
        if (quality_rank(f.quality) < quality_rank(config_.datum_min_quality)) {
            ++counters_.gps_low_quality;
            return;
        }
        frame_.emplace(Datum{f.latitude_deg, f.longitude_deg, f.height_m});
    }
    const Vector3d antenna = frame_->to_enu(f.latitude_deg, f.longitude_deg, f.height_m);
    const Matrix3d cov = fix_covariance(f);
    if (!c_.initialized) {
        if (c_.last_orientation) {
            initialize(f, antenna, cov);
        }
        return;
    }
    const UpdateResult r =
        c_.filter.update_position(antenna, cov, config_.gps_antenna_body_m, config_.gate_position_chi2);
    if (r.applied) {
        ++counters_.gps_used;
        c_.last_fix_used_utime = f.utime;
        return;
    }
    ++counters_.gps_rejected;
    if (f.utime - c_.last_fix_used_utime > config_.gps_reset_after_us) {
        // Every fix for this long disagreed with the filter: the filter, not the receiver,
        // is the one that is wrong (e.g. after a long outage with a drifting prediction).
        c_.filter.reset_position(antenna - c_.filter.state().attitude * config_.gps_antenna_body_m, cov);
        ++counters_.gps_resets;
        c_.last_fix_used_utime = f.utime;
    }
}

void PoseEstimator::initialize(const GpsFix& f, const Vector3d& antenna, const Matrix3d& cov)
{
    NominalState s;
    s.attitude = c_.last_orientation->orientation.normalized();
    s.position = antenna - s.attitude * config_.gps_antenna_body_m;
    s.velocity = Vector3d::Zero();
    s.heading_offset = 0.0;  // the IMU's yaw is taken as true until the course is seen
    const double imu_var = std::pow(imu_sigma(*c_.last_orientation), 2);
    const double yaw_var = std::pow(config_.initial_heading_sigma_rad, 2);
    const double vel_var = std::pow(config_.initial_velocity_sigma_mps, 2);
    ErrorStateFilter::Covariance P = ErrorStateFilter::Covariance::Zero();
    P.block<3, 3>(ErrorStateFilter::kP, ErrorStateFilter::kP) = cov;
    P.block<3, 3>(ErrorStateFilter::kV, ErrorStateFilter::kV) = Matrix3d::Identity() * vel_var;
    P(ErrorStateFilter::kTheta, ErrorStateFilter::kTheta) = imu_var;
    P(ErrorStateFilter::kTheta + 1, ErrorStateFilter::kTheta + 1) = imu_var;
    // True yaw is unknown by yaw_var, but IMU yaw = yaw + offset is known to imu_var.
    P(ErrorStateFilter::kTheta + 2, ErrorStateFilter::kTheta + 2) = yaw_var;
    P(ErrorStateFilter::kOffset, ErrorStateFilter::kOffset) = yaw_var + imu_var;
    P(ErrorStateFilter::kTheta + 2, ErrorStateFilter::kOffset) = -yaw_var;
    P(ErrorStateFilter::kOffset, ErrorStateFilter::kTheta + 2) = -yaw_var;
    P.block<3, 3>(ErrorStateFilter::kGyroBias, ErrorStateFilter::kGyroBias) =
        Matrix3d::Identity() * std::pow(config_.initial_gyro_bias_sigma_rps, 2);
    c_.filter.reset(s, P);
    c_.last_velocity.reset();
    c_.along_track_accel = 0.0;
    c_.accel_envelope = 0.0;

    c_.initialized = true;
    c_.heading_observed = false;
    in_outage_ = false;
    c_.filter_utime = f.utime;
    c_.last_fix_used_utime = f.utime;
    ++counters_.gps_used;
    // The first output is the first multiple of the period after the fix.
    const int64_t period = config_.output_period_us;
    c_.next_output_utime = (f.utime / period + 1) * period;
}

void PoseEstimator::apply_velocity(const GpsVelocity& v)
{
    if (!c_.initialized) {
        return;
    }
    const double speed = v.horizontal_speed_mps;
    const double sv = config_.gps_velocity_sigma_mps;
    if (speed >= config_.course_min_speed_mps) {
        double course = geometry::enu_yaw_from_track(v.track_rad);
        const double var = std::pow(config_.course_sigma_rad, 2) + std::pow(sv / speed, 2);
        if (!c_.heading_observed) {
            // First sight of the true heading: assume the vehicle drives forward.
            const double imu_var = c_.last_orientation ? std::pow(imu_sigma(*c_.last_orientation), 2)
                                                     : std::pow(config_.imu_orientation_sigma_rad, 2);
            c_.filter.align_heading(course, var, imu_var);
            c_.heading_observed = true;
            ++counters_.course_used;
        } else {
            const double yaw = geometry::euler_from_quaternion(c_.filter.state().attitude).yaw;
            if (std::cos(course - yaw) < 0.0) {
                course = geometry::wrap_angle(course + std::numbers::pi);  // reversing
            }
            const UpdateResult r = c_.filter.update_yaw(course, var, config_.gate_course_chi2);
            ++(r.applied ? counters_.course_used : counters_.course_rejected);
        }
    }
    const bool horizontal_only = std::isnan(v.vertical_speed_mps);
    const Vector3d enu(speed * std::sin(v.track_rad), speed * std::cos(v.track_rad),
                       horizontal_only ? 0.0 : v.vertical_speed_mps);
    const UpdateResult r = c_.filter.update_velocity(enu, Matrix3d::Identity() * sv * sv, config_.gps_antenna_body_m,
                                                     imu_rate(), horizontal_only, config_.gate_velocity_chi2);
    ++(r.applied ? counters_.velocity_used : counters_.velocity_rejected);
    // The speed's change over at least kAccelBaselineS: over one 0.2 s interval the velocity's
    // noise alone would read as 0.3 m/s^2.
    if (!c_.last_velocity || v.utime < c_.last_velocity->utime) {
        c_.last_velocity = v;
    } else if (v.utime - c_.last_velocity->utime >= kAccelBaselineUs) {
        c_.along_track_accel = (speed - c_.last_velocity->horizontal_speed_mps) /
                               (static_cast<double>(v.utime - c_.last_velocity->utime) * 1e-6);
        c_.last_velocity = v;
    }
}

}  // namespace ugv::estimation
