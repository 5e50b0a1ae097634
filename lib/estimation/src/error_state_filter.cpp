#include "ugv/estimation/error_state_filter.hpp"

#include <cmath>
#include <limits>

#include "ugv/geometry/rotation.hpp"

namespace ugv::estimation {

using geometry::skew;
using Eigen::Matrix3d;
using Eigen::Vector3d;

void ErrorStateFilter::reset(const NominalState& state, const Covariance& covariance)
{
    state_ = state;
    state_.attitude.normalize();
    P_ = 0.5 * (covariance + covariance.transpose());
}

bool ErrorStateFilter::healthy() const
{
    return state_.position.allFinite() && state_.velocity.allFinite() && state_.attitude.coeffs().allFinite() &&
           std::isfinite(state_.heading_offset) && state_.gyro_bias.allFinite() && P_.allFinite();
}

void ErrorStateFilter::predict(double dt, const Vector3d& rate_body, const Vector3d& specific_force_body,
                               const ProcessNoise& noise)
{
    if (!(dt > 0.0)) {
        return;
    }
    const Matrix3d r = state_.attitude.toRotationMatrix();
    const Vector3d f_world = r * specific_force_body;
    const Vector3d accel = f_world - Vector3d(0.0, 0.0, kGravity);

    state_.position += state_.velocity * dt + 0.5 * accel * dt * dt;
    state_.velocity += accel * dt;
    state_.attitude =
        (state_.attitude * geometry::quaternion_exp((rate_body - state_.gyro_bias) * dt)).normalized();

    // Error dynamics: dp' = dv, dv' = -[R f]x dtheta + R n_a, dtheta' = -R dbg - R n_g,
    // db' = n_b, dbg' = n_bg. F is formed to second order in dt (the bias reaches the
    // velocity through the attitude within the step).
    const Matrix3d fx = skew(f_world);
    const Matrix3d a_vt = -fx * dt;              // dv <- dtheta
    const Matrix3d a_pt = -0.5 * fx * dt * dt;   // dp <- dtheta
    const Matrix3d a_tb = -r * dt;               // dtheta <- dbg
    Covariance F = Covariance::Identity();
    F.block<3, 3>(kP, kV) = Matrix3d::Identity() * dt;
    F.block<3, 3>(kP, kTheta) = a_pt;
    F.block<3, 3>(kV, kTheta) = a_vt;
    F.block<3, 3>(kTheta, kGyroBias) = a_tb;
    F.block<3, 3>(kV, kGyroBias) = 0.5 * a_vt * a_tb;
    Covariance next = F * P_ * F.transpose();

    // Q of white acceleration noise integrated exactly over the step; gyro and offset noise
    // as random walks (the world-frame attitude error takes the gyro noise rotated by R,
    // which is isotropic, so R drops out).
    const double qa = noise.accel * noise.accel;
    const double qg = noise.gyro * noise.gyro;
    const double qb = noise.heading_offset * noise.heading_offset;
    const double qbg = noise.gyro_bias * noise.gyro_bias;
    for (int i = 0; i < 3; ++i) {
        next(kP + i, kP + i) += qa * dt * dt * dt / 3.0;
        next(kP + i, kV + i) += qa * dt * dt / 2.0;
        next(kV + i, kP + i) += qa * dt * dt / 2.0;
        next(kV + i, kV + i) += qa * dt;
        next(kTheta + i, kTheta + i) += qg * dt;
        next(kGyroBias + i, kGyroBias + i) += qbg * dt;
    }
    next(kOffset, kOffset) += qb * dt;
    P_ = 0.5 * (next + next.transpose());
}

template <int M>
UpdateResult ErrorStateFilter::update(const Eigen::Matrix<double, M, 1>& residual,
                                      const Eigen::Matrix<double, M, kDim>& H, const Eigen::Matrix<double, M, M>& R,
                                      double gate_chi2)
{
    UpdateResult result;
    const Eigen::Matrix<double, kDim, M> PHt = P_ * H.transpose();
    const Eigen::Matrix<double, M, M> S = H * PHt + R;
    // M <= 3: the closed-form fixed-size inverse is exact enough and cheaper than a
    // factorisation; S is positive definite whenever R is, so a bad S means bad inputs.
    const Eigen::Matrix<double, M, M> S_inv = S.inverse();
    if (!S_inv.allFinite() || !(S.diagonal().array() > 0.0).all()) {
        result.mahalanobis2 = std::numeric_limits<double>::infinity();
        return result;
    }
    result.mahalanobis2 = residual.dot(S_inv * residual);
    if (!(result.mahalanobis2 <= gate_chi2)) {
        return result;
    }
    const Eigen::Matrix<double, kDim, M> K = PHt * S_inv;
    const Covariance ikh = Covariance::Identity() - K * H;
    const Covariance next = ikh * P_ * ikh.transpose() + K * R * K.transpose();
    P_ = 0.5 * (next + next.transpose());
    inject(K * residual);
    result.applied = true;
    return result;
}

void ErrorStateFilter::inject(const Eigen::Matrix<double, kDim, 1>& dx)
{
    state_.position += dx.segment<3>(kP);
    state_.velocity += dx.segment<3>(kV);
    state_.attitude = (geometry::quaternion_exp(dx.segment<3>(kTheta)) * state_.attitude).normalized();
    state_.heading_offset = geometry::wrap_angle(state_.heading_offset + dx(kOffset));
    state_.gyro_bias += dx.segment<3>(kGyroBias);
    // The reset Jacobian of a world-frame attitude error is the identity to first order.
}

UpdateResult ErrorStateFilter::update_position(const Vector3d& antenna_enu, const Matrix3d& cov,
                                               const Vector3d& lever_body, double gate_chi2)
{
    const Vector3d lever_world = state_.attitude * lever_body;
    const Vector3d residual = antenna_enu - (state_.position + lever_world);
    Eigen::Matrix<double, 3, kDim> H = Eigen::Matrix<double, 3, kDim>::Zero();
    H.block<3, 3>(0, kP) = Matrix3d::Identity();
    H.block<3, 3>(0, kTheta) = -skew(lever_world);
    return update<3>(residual, H, cov, gate_chi2);
}

UpdateResult ErrorStateFilter::update_velocity(const Vector3d& velocity_enu, const Matrix3d& cov,
                                               const Vector3d& lever_body, const Vector3d& imu_rate_body,
                                               bool horizontal_only, double gate_chi2)
{
    // v_antenna = v + R (w x l), w = imu_rate - bg. With R_true = exp([dtheta]x) R:
    // d/d dtheta = -[R (w x l)]x, d/d dbg = R [l]x (since -(dbg x l) = l x dbg).
    const Matrix3d r = state_.attitude.toRotationMatrix();
    const Vector3d lever_velocity = r * (imu_rate_body - state_.gyro_bias).cross(lever_body);
    const Vector3d residual = velocity_enu - (state_.velocity + lever_velocity);
    Eigen::Matrix<double, 3, kDim> H = Eigen::Matrix<double, 3, kDim>::Zero();
    H.block<3, 3>(0, kV) = Matrix3d::Identity();
    H.block<3, 3>(0, kTheta) = -skew(lever_velocity);
    H.block<3, 3>(0, kGyroBias) = r * skew(lever_body);
    if (horizontal_only) {
        const Eigen::Matrix<double, 2, kDim> h2 = H.topRows<2>();
        return update<2>(residual.head<2>(), h2, cov.topLeftCorner<2, 2>(), gate_chi2);
    }
    return update<3>(residual, H, cov, gate_chi2);
}

UpdateResult ErrorStateFilter::update_imu_orientation(const Eigen::Quaterniond& imu_orientation,
                                                      const Matrix3d& cov, double gate_chi2)
{
    // Model: R_imu = Rz(b) R_true. With R_true = exp([dtheta]x) R and b = b^ + db the residual
    // log(R_imu (Rz(b^) R)^T) is Rz(b^) dtheta + e_z db to first order.
    const Matrix3d rz = geometry::rotation_z(state_.heading_offset);
    const Eigen::Quaterniond predicted(rz * state_.attitude.toRotationMatrix());
    const Vector3d residual = geometry::quaternion_log(imu_orientation * predicted.conjugate());
    Eigen::Matrix<double, 3, kDim> H = Eigen::Matrix<double, 3, kDim>::Zero();
    H.block<3, 3>(0, kTheta) = rz;
    H(2, kOffset) = 1.0;
    return update<3>(residual, H, cov, gate_chi2);
}

UpdateResult ErrorStateFilter::update_yaw(double yaw, double variance, double gate_chi2)
{
    const geometry::Euler e = geometry::euler_from_quaternion(state_.attitude);
    Eigen::Matrix<double, 1, 1> residual;
    residual(0) = geometry::wrap_angle(yaw - e.yaw);
    Eigen::Matrix<double, 1, kDim> H = Eigen::Matrix<double, 1, kDim>::Zero();
    H.block<1, 3>(0, kTheta) = geometry::euler_jacobian_world(e).row(2);
    Eigen::Matrix<double, 1, 1> R;
    R(0, 0) = variance;
    return update<1>(residual, H, R, gate_chi2);
}

void ErrorStateFilter::align_heading(double yaw, double yaw_var, double imu_yaw_var)
{
    const geometry::Euler e = geometry::euler_from_quaternion(state_.attitude);
    const double delta = geometry::wrap_angle(yaw - e.yaw);
    state_.attitude = (Eigen::Quaterniond(geometry::rotation_z(delta)) * state_.attitude).normalized();
    // The IMU yaw (= old yaw + old offset) is unchanged, so the offset takes the difference.
    state_.heading_offset = geometry::wrap_angle(state_.heading_offset - delta);
    const int yaw_index = kTheta + 2;
    P_.row(yaw_index).setZero();
    P_.col(yaw_index).setZero();
    P_.row(kOffset).setZero();
    P_.col(kOffset).setZero();
    // offset = imu_yaw - yaw: var(offset) = var(imu) + var(yaw), cov(offset, yaw) = -var(yaw).
    P_(yaw_index, yaw_index) = yaw_var;
    P_(kOffset, kOffset) = yaw_var + imu_yaw_var;
    P_(yaw_index, kOffset) = -yaw_var;
    P_(kOffset, yaw_index) = -yaw_var;
}

void ErrorStateFilter::reset_position(const Vector3d& position, const Matrix3d& cov)
{
    state_.position = position;
    P_.block<3, kDim>(kP, 0).setZero();
    P_.block<kDim, 3>(0, kP).setZero();
    P_.block<3, 3>(kP, kP) = 0.5 * (cov + cov.transpose());
}

}  // namespace ugv::estimation
