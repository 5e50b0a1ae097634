// The antenna lever arm and IMU mounting fits on a synthetic drive with known answers: stand,
// speed up, a 90 deg left turn at 2 m/s (radius 10 m, the demo's), straight on, brake, stand.
// The antenna's GPS velocity is the reference point's plus the turn's; the IMU carries noise,
// a tilt bias and a yaw rate drift. Bad drives (no turn, no motion, too short, no standing)
// say why.
#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <random>

#include "ugv/calibrate/antenna_fit.hpp"
#include "ugv/calibrate/imu_mount_fit.hpp"
#include "ugv/geometry/rotation.hpp"

using namespace ugv;
using namespace ugv::calibrate;
using Catch::Matchers::WithinAbs;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// The planar truth at 1 ms: speed, yaw rate, acceleration, heading.
struct Truth
{
    double t, v, w, a, heading;
};

struct Drive
{
    double stand_s = 10, straight_s = 15, turn_deg = 90, after_s = 5, end_stand_s = 5;
    double cruise_mps = 3, turn_mps = 2, radius_m = 10, accel_mps2 = 1;
};

std::vector<Truth> drive(const Drive& d)
{
    std::vector<Truth> out;
    Truth s{0, 0, 0, 0, 30 * kDeg};
    const double dt = 0.001;
    auto step = [&](double target, double curvature) {
        const double dv = std::clamp(target - s.v, -d.accel_mps2 * dt, d.accel_mps2 * dt);
        s.a = dv / dt;
        s.v += dv;
        s.w = curvature * s.v;
        s.heading += s.w * dt;
        s.t += dt;
        out.push_back(s);
    };
    for (double t = 0; t < d.stand_s; t += dt) step(0, 0);
    for (double t = 0; t < d.straight_s; t += dt) step(d.cruise_mps, 0);
    const double start = s.heading;
    while (d.turn_deg > 0 && s.heading - start < d.turn_deg * kDeg) step(d.turn_mps, 1 / d.radius_m);
    for (double t = 0; t < d.after_s; t += dt) step(d.turn_mps, 0);
    while (s.v > 0) step(0, 0);
    for (double t = 0; t < d.end_stand_s; t += dt) step(0, 0);
    return out;
}

struct Streams
{
    std::vector<ImuRateSample> imu;
    std::vector<GpsVelocitySample> gps;
};

// IMU at 50 Hz (noise 0.1 deg/s and 0.02 m/s^2, a 0.05 m/s^2 sideways tilt bias, a yaw rate
// drift of 0.05 deg/s), GPS velocity at 5 Hz (noise 0.02 m/s per axis) of the antenna at arm.
Streams sense(const std::vector<Truth>& truth, const Eigen::Vector2d& arm)
{
    Streams s;
    std::mt19937 rng(11);
    std::normal_distribution<double> g(0.0, 1.0);
    for (std::size_t i = 0; i < truth.size(); i += 20) {
        const Truth& m = truth[i];
        s.imu.push_back({m.t, m.w + 0.1 * kDeg * g(rng) + 0.05 * kDeg, m.a + 0.02 * g(rng), m.v * m.w + 0.05 + 0.02 * g(rng)});
    }
    for (std::size_t i = 0; i < truth.size(); i += 200) {
        const Truth& m = truth[i];
        const Eigen::Vector2d body(m.v - m.w * arm.y() + 0.02 * g(rng), m.w * arm.x() + 0.02 * g(rng));
        const Eigen::Vector2d enu = geometry::rotation_2d(m.heading) * body;
        s.gps.push_back({m.t, enu.norm(), std::atan2(enu.y(), enu.x())});
    }
    return s;
}

AntennaFitResult fit(const Drive& d, const Eigen::Vector2d& arm)
{
    const Streams s = sense(drive(d), arm);
    return fit_antenna(antenna_samples(s.imu, s.gps), 0.0, 0.0);
}

}  // namespace

TEST_CASE("the antenna's lever arm from the demo's left turn")
{
    const Eigen::Vector2d arm(0.35, -0.08);
    const AntennaFitResult r = fit({}, arm);
    INFO(r.failure);
    REQUIRE(r.failure.empty());
    CHECK(r.turn_deg > 80);
    CHECK(r.x.determined);
    CHECK(r.y.determined);
    CHECK_THAT(r.x.value, WithinAbs(arm.x(), 0.02));
    CHECK_THAT(r.y.value, WithinAbs(arm.y(), 0.04));
    CHECK(r.x.sigma < 0.03);
    CHECK(r.y.sigma < 0.04);
}

TEST_CASE("a drive without the antenna's turns says why")
{
    const Eigen::Vector2d arm(0.35, -0.08);
    SECTION("no turn")
    {
        Drive d;
        d.turn_deg = 0;
        const AntennaFitResult r = fit(d, arm);
        CHECK(r.failure.rfind("no turns: ", 0) == 0);
    }
    SECTION("no motion")
    {
        Drive d;
        d.straight_s = d.after_s = d.turn_deg = 0;
        d.cruise_mps = d.turn_mps = 0;
        const AntennaFitResult r = fit(d, arm);
        CHECK(r.failure.rfind("no motion: ", 0) == 0);
    }
    SECTION("too short")
    {
        Drive d;
        d.straight_s = 2;
        d.turn_deg = 0;
        d.after_s = 0;
        const AntennaFitResult r = fit(d, arm);
        CHECK(r.failure.rfind("too short: ", 0) == 0);
    }
}

namespace {

// The IMU as ugv-imu publishes it with the configured mounting: f = M_c M^T f_body, "up" the
// same, on a body that stands level and rolls up to +/-0.5 deg while moving (the unit's own
// attitude follows it).
std::vector<ImuMountSample> imu_samples(const std::vector<Truth>& truth, const Eigen::Vector3d& true_rpy,
                                        const Eigen::Vector3d& configured_rpy)
{
    const Eigen::Matrix3d m = geometry::rotation_from_euler({true_rpy.x(), true_rpy.y(), true_rpy.z()});
    const Eigen::Matrix3d mc = geometry::rotation_from_euler({configured_rpy.x(), configured_rpy.y(), configured_rpy.z()});
    const Eigen::Matrix3d d = mc * m.transpose();
    std::mt19937 rng(5);
    std::normal_distribution<double> g(0.0, 1.0);
    std::vector<ImuMountSample> out;
    double distance = 0, roll = 0;
    for (std::size_t i = 0; i < truth.size(); ++i) {
        distance += truth[i].v * 0.001;
        // Level where it stands: the road rolls it only while it moves.
        const double before = roll;
        roll = 0.5 * kDeg * std::sin(distance * 2.0) * std::min(1.0, truth[i].v);
        if (i % 20 != 0) continue;
        const Truth& t = truth[i];
        const double roll_rate = (roll - before) / 0.001;
        const Eigen::Matrix3d body = geometry::rotation_from_euler({roll, 0.0, 0.0});  // level frame -> body
        const Eigen::Vector3d up_body = body.transpose() * Eigen::Vector3d::UnitZ();
        const Eigen::Vector3d f_body = body.transpose() * Eigen::Vector3d(t.a, t.v * t.w, 9.80665);
        ImuMountSample s;
        s.t_s = t.t;
        s.accel_mps2 = d * f_body + 0.02 * Eigen::Vector3d(g(rng), g(rng), g(rng));
        s.rate_radps = d * Eigen::Vector3d(roll_rate, 0, t.w) + 0.1 * kDeg * Eigen::Vector3d(g(rng), g(rng), g(rng));
        s.up = d * up_body;
        s.has_up = true;
        out.push_back(s);
    }
    return out;
}

}  // namespace

TEST_CASE("the IMU's mounting from standing and straight acceleration")
{
    const Eigen::Vector3d truth(1.5 * kDeg, -1.2 * kDeg, 2.0 * kDeg);
    const Eigen::Vector3d configured = GENERATE(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.5 * kDeg, 0.3 * kDeg, -1.0 * kDeg));
    const ImuMountFitResult r = fit_imu_mount(imu_samples(drive({}), truth, configured), configured);
    INFO(r.failure);
    REQUIRE(r.failure.empty());
    CHECK(r.still_s > 12);
    CHECK(r.still_periods >= 2);
    for (int k = 0; k < kImuAngles; ++k) {
        INFO("angle " << k);
        const ParamEstimate& p = r.params[static_cast<std::size_t>(k)];
        CHECK(p.determined);
        // Yaw's sigma here is 0.07 deg (0.02 m/s^2 of noise against 250 samples at 1 m/s^2).
        CHECK_THAT(p.value / kDeg, WithinAbs(truth[k] / kDeg, k == kImuYaw ? 0.15 : 0.05));
        CHECK(p.sigma / kDeg < 0.1);
        CHECK(p.initial == configured[k]);
    }
}

TEST_CASE("a recording without standing or acceleration cannot give the IMU's mounting")
{
    const Eigen::Vector3d truth(1.5 * kDeg, -1.2 * kDeg, 2.0 * kDeg);
    SECTION("no static period")
    {
        Drive d;
        d.stand_s = d.end_stand_s = 0;
        d.straight_s = 40;  // speeds up and never stands
        d.turn_deg = 0;
        d.after_s = 0;
        std::vector<ImuMountSample> s = imu_samples(drive(d), truth, Eigen::Vector3d::Zero());
        // A rough road: the rates never settle.
        for (std::size_t i = 0; i < s.size(); ++i) s[i].rate_radps.x() += 0.05 * std::sin(static_cast<double>(i));
        const ImuMountFitResult r = fit_imu_mount(s, Eigen::Vector3d::Zero());
        CHECK(r.failure.rfind("no static period: ", 0) == 0);
    }
    SECTION("no motion")
    {
        Drive d;
        d.straight_s = d.after_s = d.turn_deg = 0;
        const ImuMountFitResult r = fit_imu_mount(imu_samples(drive(d), truth, Eigen::Vector3d::Zero()), Eigen::Vector3d::Zero());
        CHECK(r.failure.rfind("no motion: ", 0) == 0);
    }
    SECTION("too short")
    {
        std::vector<ImuMountSample> s = imu_samples(drive({}), truth, Eigen::Vector3d::Zero());
        s.resize(50);
        const ImuMountFitResult r = fit_imu_mount(s, Eigen::Vector3d::Zero());
        CHECK(r.failure.rfind("too short: ", 0) == 0);
    }
}
