// The emulated 3DM-GX1's complementary filter (tools/sim/imu/ahrs_model.cpp) against the
// small-angle solution of its equations, and the emulator's replies with it.
//
// The filter's tilt error, as a complex number z = roll + i pitch error (body axes, NED
// Euler), obeys dz/dt = -(k + i r) z + k z_ref with k = 1/tau, r the yaw rate (clockwise)
// and z_ref the reference's tilt (the gyros carry an error fixed in NED along, so in a turn
// it turns against the body; the pull is toward the body-fixed reference). From zero:
// z(t) = A (1 - exp(-(k + i r) t)), A = z_ref / (1 + i r tau). Straight, r = 0: the first
// order approach to z_ref the data sheet describes. Tolerances: the filter's 5 ms step
// (k h / 2 and r h / 2 relative, <= 0.5 %) and the second order terms of 2-6 deg errors
// (< 0.01 deg): 0.02 deg for tau = 10 s, 0.03 deg for tau = 0.5 s.
#include <catch2/catch.hpp>

#include <cmath>
#include <complex>

#include "ahrs_model.hpp"
#include "imu_emulator.hpp"
#include "ugv/microstrain_gx1/frame_parser.hpp"
#include "ugv/microstrain_gx1/orientation.hpp"
#include "ugv/microstrain_gx1/protocol.hpp"

using namespace ugv::sim::imu;
namespace gx1 = ugv::microstrain_gx1;

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
constexpr double kG = 9.80665;

// Level; straight north at v until t = 0, then a steady turn clockwise (right) at v on radius R.
AttitudeFn right_turn(double v, double radius)
{
    return [=](double t) {
        NedMotion m;
        if (t < 0) return m;
        const double r = v / radius, yaw = r * t;
        m.yaw_rad = std::remainder(yaw, 2 * kPi);
        m.rate_frd_radps = {0, 0, r};
        m.accel_ned_mps2 = {-v * r * std::sin(yaw), v * r * std::cos(yaw), 0.0};  // toward the centre
        return m;
    };
}

Eigen::Vector3d error_rpy(const AhrsModel& model, const NedMotion& m)
{
    const Eigen::Matrix3d truth = gx1::rotation_from_euler(m.roll_rad, m.pitch_rad, m.yaw_rad);
    return gx1::euler_from_rotation(truth.transpose() * model.attitude(m));
}

std::complex<double> expected_turn_error(double v, double radius, double tau, double t)
{
    const double r = v / radius;
    const std::complex<double> z_ref(-std::atan(v * r / kG), 0.0);  // outward lean: roll left in a right turn
    const std::complex<double> a = z_ref / std::complex<double>(1.0, r * tau);
    return a * (1.0 - std::exp(-std::complex<double>(1.0 / tau, r) * t));
}

}  // namespace

TEST_CASE("AHRS: a steady turn gives the false roll (and pitch) of the filter's equations after 3 time constants",
          "[gx1][ahrs]")
{
    const double v = 2.0, radius = 10.0;  // 0.4 m/s^2: the reference leans atan(0.4 / g) = 2.34 deg outward
    for (const double tau : {10.0, 0.5}) {
        AhrsConfig c;
        c.time_constant_s = tau;
        const AttitudeFn truth = right_turn(v, radius);
        AhrsModel model(c, -5.0, truth);
        const double t = 3 * tau;
        model.advance(t);
        const Eigen::Vector3d e = error_rpy(model, truth(t));
        const std::complex<double> want = expected_turn_error(v, radius, tau, t);
        const double tol = tau > 1 ? 0.02 : 0.03;
        INFO("tau " << tau << ": roll " << e.x() / kDeg << " pitch " << e.y() / kDeg << " deg; expected "
                    << want.real() / kDeg << ", " << want.imag() / kDeg);
        CHECK(e.x() / kDeg == Approx(want.real() / kDeg).margin(tol));
        CHECK(e.y() / kDeg == Approx(want.imag() / kDeg).margin(tol));
        if (tau < 1) {
            // Turning slowly against the filter (r tau = 0.1): nearly the whole 2.3 deg, as roll.
            CHECK(e.x() / kDeg < -2.2);
        } else {
            // r tau = 2 (the demo's turn): the error turns with the body; |A| = 2.34 / sqrt(5).
            CHECK(std::hypot(e.x(), e.y()) / kDeg == Approx(2.3356 / std::sqrt(5.0) * 0.955).margin(0.05));
        }
    }
}

TEST_CASE("AHRS: straight at constant speed gives no false tilt; the heading is off by the disturbance",
          "[gx1][ahrs]")
{
    AhrsConfig c;
    c.mag_disturbance_rad = 2.0 * kDeg;
    const AttitudeFn truth = [](double) {
        NedMotion m;
        m.yaw_rad = 0.5;  // constant speed, constant heading: no acceleration
        return m;
    };
    AhrsModel model(c, 0.0, truth);
    for (double t = 1; t <= 60; t += 1) {
        model.advance(t);
        const Eigen::Vector3d e = error_rpy(model, truth(t));
        REQUIRE(std::abs(e.x()) < 1e-9);
        REQUIRE(std::abs(e.y()) < 1e-9);
        REQUIRE(e.z() == Approx(model.heading_error_rad(0.5)).margin(1e-9));
    }
    CHECK(std::abs(model.heading_error_rad(0.5)) <= 2.0 * kDeg);
}

TEST_CASE("AHRS: braking gives a false nose-down pitch approached with the time constant", "[gx1][ahrs]")
{
    // Heading north at 3 m/s, braking at 1 m/s^2 from t = 0 to 3 s: the reference pitches
    // atan(1 / g) = 5.82 deg nose down (NED pitch negative; the project's FLU pitch positive).
    const AttitudeFn truth = [](double t) {
        NedMotion m;
        if (t >= 0 && t < 3) m.accel_ned_mps2 = {-1.0, 0.0, 0.0};
        return m;
    };
    AhrsConfig c;
    AhrsModel model(c, -1.0, truth);
    model.advance(3.0 - 1e-9);
    const Eigen::Vector3d e = error_rpy(model, truth(3.0 - 1e-9));
    const double want = -std::atan(1.0 / kG) * (1.0 - std::exp(-3.0 / c.time_constant_s));
    CHECK(e.y() < 0);
    CHECK(e.y() / kDeg == Approx(want / kDeg).margin(0.02));
    CHECK(std::abs(e.x()) < 1e-6);
    // Standing again, the error decays with the same time constant.
    model.advance(3.0 + c.time_constant_s);
    CHECK(error_rpy(model, truth(13.0)).y() / kDeg == Approx(want / kDeg * std::exp(-1.0)).margin(0.02));
}

TEST_CASE("AHRS: the gyro bias walks with the configured spread and one seed gives one history", "[gx1][ahrs]")
{
    // Var(b(T)) = q^2 T per axis. 200 seeds x 3 axes: the variance's relative standard error is
    // sqrt(2 / 600) = 6 %; 25 % is four of them.
    const double q = 0.01 * kDeg, horizon = 100.0;
    const AttitudeFn still = [](double) { return NedMotion{}; };
    double sum2 = 0;
    int n = 0;
    for (unsigned seed = 1; seed <= 200; ++seed) {
        AhrsConfig c;
        c.gyro_bias_walk_radps_per_sqrt_s = q;
        c.step_s = 0.05;
        c.seed = seed;
        AhrsModel model(c, 0.0, still);
        const Eigen::Vector3d b = model.advance(horizon).gyro_bias_radps;
        for (int i = 0; i < 3; ++i) sum2 += b[i] * b[i];
        n += 3;
    }
    CHECK(sum2 / n == Approx(q * q * horizon).epsilon(0.25));

    AhrsConfig c;
    c.gyro_bias_walk_radps_per_sqrt_s = q;
    c.mag_disturbance_rad = 1.0 * kDeg;
    AhrsModel a(c, 0.0, right_turn(2.0, 10.0)), b(c, 0.0, right_turn(2.0, 10.0));
    a.advance(7.3);  // asked at other times: the same state on the grid
    for (double t = 0.013; t < 7.3; t += 0.37) b.advance(t);
    b.advance(7.3);
    CHECK(a.advance(7.3).gyro_bias_radps == b.advance(7.3).gyro_bias_radps);
    CHECK(a.advance(7.3).error == b.advance(7.3).error);
}

TEST_CASE("AHRS in the emulator: the attitude is the filter's, rates and accelerations the sensors' truth",
          "[gx1][ahrs][emulator]")
{
    const double v = 2.0, radius = 10.0, tau = 10.0;
    EmulatorConfig ec;
    ec.attitude = right_turn(v, radius);
    AhrsConfig a;
    a.time_constant_s = tau;
    ec.ahrs = a;
    ec.ahrs_start_s = -5.0;
    Gx1Emulator emu(ec, -5.0);
    const double t = 3 * tau;
    gx1::FrameParser parser;
    const std::vector<uint8_t> bytes = emu.data_reply(gx1::cmd::stab_euler_accel_rate, t);
    parser.feed(bytes.data(), bytes.size());
    gx1::Frame f;
    REQUIRE(parser.next(f));
    const gx1::DeviceSample s = gx1::decode_sample(f, gx1::GainScales{});
    const std::complex<double> want = expected_turn_error(v, radius, tau, t);
    const double yaw = std::remainder(v / radius * t, 2 * kPi);
    // Euler words resolve 0.0055 deg.
    CHECK(s.roll_rad / kDeg == Approx(want.real() / kDeg).margin(0.03));
    CHECK(s.pitch_rad / kDeg == Approx(want.imag() / kDeg).margin(0.03));
    // The heading follows a magnetometer levelled with the false tilt; the field dips 66 deg,
    // so a 1 deg tilt error turns the reference by up to tan(66 deg) = 2.2 deg.
    CHECK(std::abs(std::remainder(s.yaw_rad - yaw, 2 * kPi)) / kDeg < 2.5);
    // The accelerometers see the level body's specific force (0, v r, -g), not the filter's tilt.
    CHECK(s.accel_mps2[0] == Approx(0.0).margin(0.01));
    CHECK(s.accel_mps2[1] == Approx(v * v / radius).margin(0.01));
    CHECK(s.accel_mps2[2] == Approx(-kG).margin(0.01));
    CHECK(s.rate_radps[2] == Approx(v / radius).margin(1e-3));
}
