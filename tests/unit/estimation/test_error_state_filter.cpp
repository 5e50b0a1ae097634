#include <catch2/catch.hpp>

#include <cmath>

#include "ugv/estimation/error_state_filter.hpp"
#include "ugv/geometry/rotation.hpp"

using namespace ugv::estimation;
using Eigen::Matrix3d;
using Eigen::Vector3d;
using F = ErrorStateFilter;

static ErrorStateFilter make(double pos_var = 1.0)
{
    ErrorStateFilter f;
    F::Covariance P = F::Covariance::Identity() * 0.01;
    P.block<3, 3>(F::kP, F::kP) = Matrix3d::Identity() * pos_var;
    f.reset(NominalState{}, P);
    return f;
}

static const Vector3d kLevelForce(0.0, 0.0, F::kGravity);  // specific force at rest, level

TEST_CASE("at rest and level, prediction leaves the state where it is")
{
    ErrorStateFilter f = make();
    for (int i = 0; i < 100; ++i) {
        f.predict(0.01, Vector3d::Zero(), kLevelForce, ProcessNoise{});
    }
    CHECK(f.state().position.norm() < 1e-12);
    CHECK(f.state().velocity.norm() < 1e-12);
}

TEST_CASE("constant forward acceleration integrates exactly (0.5 a t^2)")
{
    ErrorStateFilter f = make();
    NominalState s;
    s.attitude = ugv::geometry::quaternion_from_euler({0.0, 0.0, M_PI / 2});  // facing north
    f.reset(s, f.covariance());
    for (int i = 0; i < 200; ++i) {
        f.predict(0.01, Vector3d::Zero(), Vector3d(1.5, 0.0, F::kGravity), ProcessNoise{});
    }
    CHECK(f.state().position.y() == Approx(0.5 * 1.5 * 4.0).epsilon(1e-12));
    CHECK(f.state().velocity.y() == Approx(3.0).epsilon(1e-12));
    CHECK(std::fabs(f.state().position.x()) < 1e-9);
}

TEST_CASE("body rate turns the attitude: 0.5 rad/s for 2 s is 1 rad of yaw")
{
    ErrorStateFilter f = make();
    for (int i = 0; i < 200; ++i) {
        f.predict(0.01, Vector3d(0, 0, 0.5), kLevelForce, ProcessNoise{});
    }
    CHECK(ugv::geometry::euler_from_quaternion(f.state().attitude).yaw == Approx(1.0).epsilon(1e-9));
}

TEST_CASE("velocity variance grows by accel_density^2 * t, yaw by gyro_density^2 * t")
{
    // No attitude uncertainty, so that gravity does not leak tilt error into velocity.
    ErrorStateFilter f;
    F::Covariance P0 = F::Covariance::Zero();
    P0.block<3, 3>(F::kP, F::kP) = Matrix3d::Identity();
    f.reset(NominalState{}, P0);
    ProcessNoise n;
    n.accel = 0.2;
    n.gyro = 1e-7;
    n.gyro_bias = 1e-12;
    for (int i = 0; i < 100; ++i) {
        f.predict(0.01, Vector3d::Zero(), kLevelForce, n);
    }
    CHECK(f.covariance()(F::kV, F::kV) == Approx(0.04).epsilon(1e-6));
    // Position: P0 + q t^3 / 3 (from the velocity noise integrated twice).
    CHECK(f.covariance()(F::kP, F::kP) == Approx(1.0 + 0.04 / 3.0).epsilon(1e-6));

    ErrorStateFilter g;
    g.reset(NominalState{}, P0);
    n.gyro = 0.01;
    for (int i = 0; i < 100; ++i) {
        g.predict(0.01, Vector3d::Zero(), kLevelForce, n);
    }
    CHECK(g.covariance()(F::kTheta + 2, F::kTheta + 2) == Approx(1e-4).epsilon(1e-9));
}

TEST_CASE("a position update with equal prior and measurement variance halves the variance")
{
    ErrorStateFilter f = make(4.0);
    const UpdateResult r =
        f.update_position(Vector3d(2.0, 0.0, 0.0), Matrix3d::Identity() * 4.0, Vector3d::Zero(), 16.27);
    REQUIRE(r.applied);
    // Innovation 2 m, S = 8 m^2: d^2 = 4 / 8.
    CHECK(r.mahalanobis2 == Approx(0.5));
    CHECK(f.state().position.x() == Approx(1.0));
    CHECK(f.covariance()(F::kP, F::kP) == Approx(2.0));
}

TEST_CASE("a position far outside the gate is refused and changes nothing")
{
    ErrorStateFilter f = make(0.25);
    const F::Covariance before = f.covariance();
    const UpdateResult r =
        f.update_position(Vector3d(30.0, 0.0, 0.0), Matrix3d::Identity() * 0.25, Vector3d::Zero(), 16.27);
    CHECK_FALSE(r.applied);
    CHECK(r.mahalanobis2 == Approx(900.0 / 0.5));
    CHECK(f.state().position.norm() == 0.0);
    CHECK(f.covariance() == before);
}

TEST_CASE("the lever arm: an antenna 1 m ahead of a north-facing vehicle is 1 m north of it")
{
    ErrorStateFilter f = make(100.0);
    NominalState s;
    s.attitude = ugv::geometry::quaternion_from_euler({0.0, 0.0, M_PI / 2});
    f.reset(s, f.covariance());
    // The antenna reads exactly where the lever arm puts it: no innovation.
    const UpdateResult r =
        f.update_position(Vector3d(0.0, 1.0, 0.0), Matrix3d::Identity() * 1e-4, Vector3d(1.0, 0.0, 0.0), 16.27);
    CHECK(r.mahalanobis2 == Approx(0.0).margin(1e-12));
    CHECK(f.state().position.norm() < 1e-9);
}

TEST_CASE("IMU orientation: the residual yaw splits between yaw and offset by their variances")
{
    ErrorStateFilter f;
    F::Covariance P = F::Covariance::Identity() * 1e-6;
    P(F::kTheta + 2, F::kTheta + 2) = 0.01;
    P(F::kOffset, F::kOffset) = 0.03;
    f.reset(NominalState{}, P);
    const Eigen::Quaterniond imu(Eigen::AngleAxisd(0.1, Vector3d::UnitZ()));
    const UpdateResult r = f.update_imu_orientation(imu, Matrix3d::Identity() * 1e-8, 1e9);
    REQUIRE(r.applied);
    const double yaw = ugv::geometry::euler_from_quaternion(f.state().attitude).yaw;
    // Nearly noiseless measurement: yaw + offset = 0.1, split 1:3.
    CHECK(yaw + f.state().heading_offset == Approx(0.1).epsilon(1e-5));
    CHECK(yaw == Approx(0.025).epsilon(1e-3));
    CHECK(f.state().heading_offset == Approx(0.075).epsilon(1e-3));
}

TEST_CASE("align_heading sets true yaw and moves the difference into the offset")
{
    ErrorStateFilter f = make();
    NominalState s;
    s.attitude = ugv::geometry::quaternion_from_euler({0.02, -0.01, 1.0});
    s.heading_offset = 0.1;  // IMU yaw = 1.1
    f.reset(s, f.covariance());
    f.align_heading(0.4, 0.0025, 0.0001);
    const auto e = ugv::geometry::euler_from_quaternion(f.state().attitude);
    CHECK(e.yaw == Approx(0.4));
    CHECK(e.roll == Approx(0.02).margin(1e-3));
    CHECK(f.state().heading_offset == Approx(0.7));  // still 1.1 in IMU yaw
    CHECK(f.covariance()(F::kTheta + 2, F::kTheta + 2) == Approx(0.0025));
    CHECK(f.covariance()(F::kOffset, F::kOffset) == Approx(0.0026));
    CHECK(f.covariance()(F::kOffset, F::kTheta + 2) == Approx(-0.0025));
}

TEST_CASE("yaw update wraps across +-pi")
{
    ErrorStateFilter f = make();
    NominalState s;
    s.attitude = ugv::geometry::quaternion_from_euler({0.0, 0.0, 3.1});
    f.reset(s, f.covariance());
    // -3.1 is 0.083 rad away through pi, not 6.2.
    const UpdateResult r = f.update_yaw(-3.1, 1e-8, 10.83);
    REQUIRE(r.applied);
    CHECK(std::fabs(ugv::geometry::euler_from_quaternion(f.state().attitude).yaw) == Approx(3.1).epsilon(1e-4));
    CHECK(r.mahalanobis2 == Approx(std::pow(2 * M_PI - 6.2, 2) / 0.01).epsilon(1e-3));
}

TEST_CASE("horizontal-only velocity leaves the vertical alone; a NaN state reports unhealthy")
{
    ErrorStateFilter f = make();
    f.update_velocity(Vector3d(1.0, 2.0, 0.0), Matrix3d::Identity() * 1e-6, Vector3d::Zero(), Vector3d::Zero(), true,
                      1e9);
    CHECK(f.state().velocity.x() == Approx(1.0).epsilon(1e-3));
    CHECK(f.state().velocity.y() == Approx(2.0).epsilon(1e-3));
    CHECK(f.covariance()(F::kV + 2, F::kV + 2) == Approx(0.01));
    CHECK(f.healthy());
    f.predict(0.01, Vector3d(NAN, 0, 0), kLevelForce, ProcessNoise{});
    CHECK_FALSE(f.healthy());
}

TEST_CASE("the lever arm in velocity: a vehicle turning in place moves its antenna by R (w x l)")
{
    // Facing north, turning left at 0.5 rad/s, antenna 2 m ahead: the antenna moves west at
    // 1 m/s while the reference point stands.
    ErrorStateFilter f = make();
    NominalState s;
    s.attitude = ugv::geometry::quaternion_from_euler({0.0, 0.0, M_PI / 2});
    f.reset(s, f.covariance());
    const Vector3d rate(0.0, 0.0, 0.5), lever(2.0, 0.0, 0.0);
    const UpdateResult r =
        f.update_velocity(Vector3d(-1.0, 0.0, 0.0), Matrix3d::Identity() * 1e-4, lever, rate, false, 16.27);
    CHECK(r.applied);
    CHECK(r.mahalanobis2 == Approx(0.0).margin(1e-12));
    CHECK(f.state().velocity.norm() < 1e-9);
    // Without the lever arm the same measurement would be read as the vehicle moving west.
    ErrorStateFilter g = make();
    g.reset(s, g.covariance());
    g.update_velocity(Vector3d(-1.0, 0.0, 0.0), Matrix3d::Identity() * 1e-4, Vector3d::Zero(), rate, false, 1e9);
    CHECK(g.state().velocity.x() < -0.9);
}

TEST_CASE("the gyro bias is taken off the rate, and its uncertainty grows the attitude's")
{
    ErrorStateFilter f;
    F::Covariance P = F::Covariance::Identity() * 1e-6;
    P.block<3, 3>(F::kGyroBias, F::kGyroBias) = Matrix3d::Identity() * 1e-4;
    NominalState s;
    s.gyro_bias = Vector3d(0.0, 0.0, 0.01);
    f.reset(s, P);
    ProcessNoise noise;
    noise.gyro = 1e-9;
    for (int i = 0; i < 100; ++i) {
        f.predict(0.01, Vector3d(0.0, 0.0, 0.01), kLevelForce, noise);  // the rate is all bias
    }
    CHECK(std::fabs(ugv::geometry::euler_from_quaternion(f.state().attitude).yaw) < 1e-12);
    // 1 s of an uncertain bias (sigma 0.01 rad/s): yaw variance 1e-6 + 1e-4 * 1^2.
    CHECK(f.covariance()(F::kTheta + 2, F::kTheta + 2) == Approx(1.01e-4).epsilon(0.02));
    CHECK(f.covariance()(F::kTheta + 2, F::kGyroBias + 2) == Approx(-1e-4).epsilon(0.02));
}
