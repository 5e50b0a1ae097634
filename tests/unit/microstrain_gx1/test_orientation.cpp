// The NED -> ENU conversion, with attitudes worked out by hand.
#include <catch2/catch.hpp>

#include <cmath>

#include "ugv/microstrain_gx1/orientation.hpp"

using namespace ugv::microstrain_gx1;

namespace {
constexpr double pi = 3.14159265358979323846;
constexpr double deg = pi / 180.0;

void check_quaternion(const Eigen::Quaterniond& q, double w, double x, double y, double z)
{
    CHECK(q.w() == Approx(w).margin(1e-12));
    CHECK(q.x() == Approx(x).margin(1e-12));
    CHECK(q.y() == Approx(y).margin(1e-12));
    CHECK(q.z() == Approx(z).margin(1e-12));
}
}  // namespace

TEST_CASE("roll 10, pitch -5, yaw 90 (NED) -> the hand-computed ENU quaternion", "[gx1][orientation]")
{
    // Device: roll 10 deg (right side down), pitch -5 deg (nose down), heading 90 deg (east).
    // In FLU/ENU: roll stays 10 deg; pitch about the LEFT axis is +5 deg (nose down is
    // positive); heading east is ENU yaw 0. So q = qz(0) * qy(5 deg) * qx(10 deg):
    //   qy(5) = (cos 2.5, 0, sin 2.5, 0), qx(10) = (cos 5, sin 5, 0, 0)
    //   product = (c2.5 c5, c2.5 s5, s2.5 c5, -s2.5 s5)
    //           = (0.99524654, 0.08707279, 0.04345340, -0.00380168)
    const EnuAttitude a = enu_from_ned_euler(10 * deg, -5 * deg, 90 * deg);
    const double c25 = std::cos(2.5 * deg), s25 = std::sin(2.5 * deg), c5 = std::cos(5 * deg), s5 = std::sin(5 * deg);
    check_quaternion(a.q_enu_body, c25 * c5, c25 * s5, s25 * c5, -s25 * s5);
    CHECK(a.q_enu_body.w() == Approx(0.9952465414778341).margin(1e-12));
    CHECK(a.q_enu_body.x() == Approx(0.0870727897926938).margin(1e-12));
    CHECK(a.q_enu_body.y() == Approx(0.0434534024273578).margin(1e-12));
    CHECK(a.q_enu_body.z() == Approx(-0.0038016801040237).margin(1e-12));
    CHECK(a.roll_rad == Approx(10 * deg));
    CHECK(a.pitch_rad == Approx(5 * deg));
    CHECK(a.yaw_rad == Approx(0.0).margin(1e-12));  // ENU heading: east

    // Physically: the nose points east and 5 deg down; the left side is up.
    const Eigen::Vector3d nose = a.q_enu_body * Eigen::Vector3d::UnitX();
    CHECK(nose.x() == Approx(std::cos(5 * deg)));
    CHECK(nose.y() == Approx(0.0).margin(1e-12));
    CHECK(nose.z() == Approx(-std::sin(5 * deg)));
    const Eigen::Vector3d left = a.q_enu_body * Eigen::Vector3d::UnitY();
    CHECK(left.z() == Approx(std::sin(10 * deg) * std::cos(5 * deg)));
}

TEST_CASE("ENU heading of level attitudes: yaw_enu = 90 deg - yaw_ned", "[gx1][orientation]")
{
    struct Case { double ned_deg, enu_deg; };
    for (Case c : {Case{0, 90}, Case{90, 0}, Case{45, 45}, Case{-90, 180}, Case{180, -90}, Case{135, -45}}) {
        INFO("NED heading " << c.ned_deg);
        const EnuAttitude a = enu_from_ned_euler(0, 0, c.ned_deg * deg);
        const double err = std::remainder(a.yaw_rad - c.enu_deg * deg, 2 * pi);
        CHECK(err == Approx(0.0).margin(1e-12));
        CHECK(a.roll_rad == Approx(0.0).margin(1e-12));
        CHECK(a.pitch_rad == Approx(0.0).margin(1e-12));
        // A level attitude is a pure rotation about up: (cos(h/2), 0, 0, sin(h/2)), w >= 0.
        const double h = c.enu_deg * deg;
        const double sign = std::cos(h / 2) < 0 ? -1.0 : 1.0;
        check_quaternion(a.q_enu_body, sign * std::cos(h / 2), 0, 0, sign * std::sin(h / 2));
    }
}

TEST_CASE("magnetic declination turns magnetic into true heading", "[gx1][orientation]")
{
    // Declination 10 deg east: magnetic heading 80 deg is true 90 deg = ENU yaw 0.
    const EnuAttitude a = enu_from_ned_euler(0, 0, 80 * deg, 10 * deg);
    CHECK(a.yaw_rad == Approx(0.0).margin(1e-12));
}

TEST_CASE("the device quaternion gives the same attitude as the Euler angles", "[gx1][orientation]")
{
    // ZYX Euler -> quaternion by the textbook half-angle formula (NED, sensor -> NED).
    const double r = 10 * deg / 2, p = -5 * deg / 2, y = 90 * deg / 2;
    const Eigen::Quaterniond q_ned(std::cos(r) * std::cos(p) * std::cos(y) + std::sin(r) * std::sin(p) * std::sin(y),
                                   std::sin(r) * std::cos(p) * std::cos(y) - std::cos(r) * std::sin(p) * std::sin(y),
                                   std::cos(r) * std::sin(p) * std::cos(y) + std::sin(r) * std::cos(p) * std::sin(y),
                                   std::cos(r) * std::cos(p) * std::sin(y) - std::sin(r) * std::sin(p) * std::cos(y));
    const EnuAttitude a = enu_from_ned_quaternion(q_ned);
    const double c25 = std::cos(2.5 * deg), s25 = std::sin(2.5 * deg), c5 = std::cos(5 * deg), s5 = std::sin(5 * deg);
    check_quaternion(a.q_enu_body, c25 * c5, c25 * s5, s25 * c5, -s25 * s5);
}

TEST_CASE("FrameConverter: vectors into FLU, matrices and mounting", "[gx1][orientation]")
{
    DeviceSample s;
    s.has_euler = s.has_accel = s.has_rate = s.has_mag = true;
    s.yaw_rad = 90 * deg;
    s.accel_mps2 = {0, 0, -9.80665};  // level: specific force points up = -Z in FRD
    s.rate_radps = {0.1, 0.2, 0.3};   // +Z FRD = turning right
    s.mag_gauss = {0.2, 0.0, 0.4};
    const Measurement m = FrameConverter().convert(s);
    CHECK(m.has_orientation);
    CHECK(m.accel_mps2.z() == Approx(9.80665));
    CHECK(m.rate_radps.x() == Approx(0.1));
    CHECK(m.rate_radps.y() == Approx(-0.2));
    CHECK(m.rate_radps.z() == Approx(-0.3));  // turning right = negative yaw rate in FLU
    CHECK(m.mag_gauss.z() == Approx(-0.4));

    // Sensor mounted turned 90 deg to the left on the body: sensor forward = body left.
    // The sensor faces east, so the body faces south (ENU yaw -90 deg), and a sensor
    // forward acceleration is a body leftward one.
    const FrameConverter mounted(rotation_from_euler(0, 0, 90 * deg));
    s.accel_mps2 = {1.0, 0, 0};
    const Measurement mm = mounted.convert(s);
    CHECK(mm.attitude.yaw_rad == Approx(-90 * deg));
    CHECK(mm.accel_mps2.y() == Approx(1.0));
    CHECK(mm.accel_mps2.x() == Approx(0.0).margin(1e-12));

    // An orientation matrix M (NED -> sensor) for heading 90 deg: R_ned_frd = Rz(90), M = R^T.
    DeviceSample ms;
    ms.has_matrix = true;
    ms.matrix = {0, 1, 0, -1, 0, 0, 0, 0, 1};
    CHECK(FrameConverter().convert(ms).attitude.yaw_rad == Approx(0.0).margin(1e-12));

    // No attitude in a temperature reply.
    DeviceSample t;
    t.has_temperature = true;
    CHECK_FALSE(FrameConverter().convert(t).has_orientation);
}
