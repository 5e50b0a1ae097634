// The error-state Kalman filter at the core of the pose estimator, without any timing,
// buffering or input policy (those live in PoseEstimator).
//
// Nominal state: position p and velocity v of the body reference point in local ENU (m, m/s),
// attitude q (body -> ENU), the heading offset b of the IMU (rad): the IMU's magnetic
// yaw is true yaw + b (magnetic declination plus mounting and compass error), and the gyro
// bias bg (body, rad/s): the IMU's rate is the true rate + bg.
// Error state (13): dp(3), dv(3), dtheta(3) (attitude error as a world-frame rotation vector,
// R_true = exp([dtheta]x) R), db(1), dbg(3).
//
// The IMU's rate (less bg) and specific force drive the prediction (strapdown mechanisation
// with gravity 9.80665 m/s^2 along -Up); measurements correct it. A tilt error dtheta makes
// the specific force rotated into the world lean by g dtheta, which the GPS velocity sees:
// that, not the IMU's own attitude output, is what holds roll and pitch. Every update is gated on its
// Mahalanobis distance and uses the Joseph form so that P stays symmetric positive definite.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ugv::estimation {

struct NominalState
{
    Eigen::Vector3d position = Eigen::Vector3d::Zero();  // m, ENU
    Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // m/s, ENU
    Eigen::Quaterniond attitude = Eigen::Quaterniond::Identity();  // body -> ENU
    double heading_offset = 0.0;  // rad, IMU yaw minus true yaw
    Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();  // rad/s, body: IMU rate minus true rate
};

// Continuous-time process noise densities.
struct ProcessNoise
{
    double accel = 0.1;           // m/s^2/sqrt(Hz): white noise on the specific force
    double gyro = 0.005;          // rad/s/sqrt(Hz): white noise on the body rate
    double heading_offset = 1e-4; // rad/sqrt(s): random walk of the IMU heading offset
    double gyro_bias = 1e-5;      // rad/s/sqrt(s): random walk of each gyro's bias
};

// What an update did: the squared Mahalanobis distance of its innovation, and whether it
// passed the gate (and so was applied).
struct UpdateResult
{
    double mahalanobis2 = 0.0;
    bool applied = false;
};

class ErrorStateFilter
{
public:
    static constexpr int kDim = 13;
    static constexpr int kP = 0, kV = 3, kTheta = 6, kOffset = 9, kGyroBias = 10;  // error-state offsets
    using Covariance = Eigen::Matrix<double, kDim, kDim>;
    static constexpr double kGravity = 9.80665;  // m/s^2

    // Starts from a state and a covariance (must be symmetric positive definite).
    void reset(const NominalState& state, const Covariance& covariance);

    const NominalState& state() const { return state_; }
    const Covariance& covariance() const { return P_; }
    // False once a non-finite number appears in the state or its covariance.
    bool healthy() const;

    // Propagates by dt (s) with the IMU's body rate (rad/s, the bias is removed here) and
    // specific force (m/s^2) held constant over the step.
    void predict(double dt, const Eigen::Vector3d& rate_body, const Eigen::Vector3d& specific_force_body,
                 const ProcessNoise& noise);

    // GPS antenna position (ENU, m) with covariance; the antenna sits at lever_body from the
    // reference point (body frame, m).
    UpdateResult update_position(const Eigen::Vector3d& antenna_enu, const Eigen::Matrix3d& cov,
                                 const Eigen::Vector3d& lever_body, double gate_chi2);
    // Velocity over ground of the GPS antenna (ENU, m/s), which sits at lever_body: the
    // reference point's velocity plus R (w x lever), w the IMU's rate (rad/s, body) less the
    // bias. horizontal_only uses the east and north components.
    UpdateResult update_velocity(const Eigen::Vector3d& velocity_enu, const Eigen::Matrix3d& cov,
                                 const Eigen::Vector3d& lever_body, const Eigen::Vector3d& imu_rate_body,
                                 bool horizontal_only, double gate_chi2);
    // The IMU's orientation (body -> ENU with its magnetic yaw), cov in its world-frame
    // rotation vector (rad^2).
    UpdateResult update_imu_orientation(const Eigen::Quaterniond& imu_orientation, const Eigen::Matrix3d& cov,
                                        double gate_chi2);
    // A direct observation of true yaw (rad, ENU) with variance (rad^2), e.g. course over ground.
    UpdateResult update_yaw(double yaw, double variance, double gate_chi2);

    // Sets true yaw to yaw (variance yaw_var) keeping roll and pitch, and the heading offset so
    // that the IMU's current yaw stays explained; the IMU yaw's own variance is imu_yaw_var.
    // Used once, when the heading is first observed: a correction too large to linearise.
    void align_heading(double yaw, double yaw_var, double imu_yaw_var);
    // Re-anchors the position (reference point, ENU) with covariance; cross terms cleared.
    void reset_position(const Eigen::Vector3d& position, const Eigen::Matrix3d& cov);

private:
    template <int M>
    UpdateResult update(const Eigen::Matrix<double, M, 1>& residual, const Eigen::Matrix<double, M, kDim>& H,
                        const Eigen::Matrix<double, M, M>& R, double gate_chi2);
    void inject(const Eigen::Matrix<double, kDim, 1>& dx);

    NominalState state_;
    Covariance P_ = Covariance::Identity();
};

}  // namespace ugv::estimation
