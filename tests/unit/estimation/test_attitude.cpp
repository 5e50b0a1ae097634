// Roll and pitch under an AHRS that takes the vehicle's acceleration for tilt, and the gyro
// bias: synthetic runs (tests/unit/estimation/synthetic.hpp) driven through the estimator.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "run_helpers.hpp"

using namespace ugv::estimation;
using namespace ugv::estimation::synthetic;

namespace {

constexpr double kDeg = M_PI / 180.0;

struct TiltScore
{
    double rms = 0.0, max = 0.0;  // rad, of the tilt (roll and pitch together)
    int n = 0;
};

// Tilt error of the horizontal part of the world rotation vector from a to the truth.
void add(TiltScore& s, const Eigen::Quaterniond& a, const Truth& t)
{
    const Eigen::Vector3d e = ugv::geometry::quaternion_log(t.attitude() * a.conjugate());
    const double tilt = e.head<2>().norm();
    s.rms += tilt * tilt;
    s.max = std::max(s.max, tilt);
    ++s.n;
}

void finish(TiltScore& s)
{
    REQUIRE(s.n > 0);
    s.rms = std::sqrt(s.rms / s.n);
}

// The simulator's GX1 (docs/simulator.md): 0.1 deg/s and 0.02 m/s^2 of white noise per 50 Hz
// sample. The default synthetic noise (0.005 rad/s/sqrt(Hz)) makes the tilt walk 0.3 deg in
// a few seconds, more than any filter can hold to 0.3 deg.
Noise quiet_imu()
{
    Noise n;
    n.gyro_density = 0.00025;
    n.accel_density = 0.003;
    return n;
}

double seconds(const Run& run, int64_t utime)
{
    return static_cast<double>(utime - run.start_utime) * 1e-6;
}

}  // namespace

TEST_CASE("acceleration compensation: the IMU's tilt sigma grows with the vehicle's acceleration")
{
    const Noise noise = quiet_imu();  // IMU orientation sigma 0.01 rad
    SECTION("a steady turn of 0.5 m/s^2 adds 0.5 / g")
    {
        const Trajectory t = circle(50.0, 5.0);
        const Run run = simulate(t, noise, kTestDatum, 30.0, 3);
        PoseEstimator est(matched_config(noise));
        const std::vector<PoseEstimate> poses = run_all(est, run.inputs);
        REQUIRE(!poses.empty());
        // The envelope keeps the peaks of the GPS velocity's noise (0.05 m/s per axis): a little
        // above the turn's own 0.5 m/s^2.
        const double expected = std::hypot(0.01, 0.5 / ErrorStateFilter::kGravity);
        CHECK(poses.back().imu_tilt_sigma > 0.98 * expected);
        CHECK(poses.back().imu_tilt_sigma < 1.25 * expected);
    }
    SECTION("driving straight at constant speed, the braking's inflation decays with the time constant")
    {
        const Trajectory t = straight(0.3, 1.0, 3.0);  // 1 m/s^2 for 3 s, then 3 m/s
        const Run run = simulate(t, noise, kTestDatum, 60.0, 3);
        PoseEstimator est(matched_config(noise));
        const std::vector<PoseEstimate> poses = run_all(est, run.inputs);
        double during = 0.0;
        for (const PoseEstimate& p : poses) {
            if (std::fabs(seconds(run, p.utime) - 2.5) < 0.05) {
                during = p.imu_tilt_sigma;
            }
        }
        CHECK(during > 0.08);  // ~1 m/s^2 / g, from the GPS velocity's change
        CHECK(poses.back().imu_tilt_sigma < 0.3 * during);
    }
}

TEST_CASE("gyro bias: estimated from the GPS velocity and course, the attitude does not drift with it")
{
    Noise noise = quiet_imu();
    noise.gyro_bias_rps = Eigen::Vector3d(0.004, -0.003, 0.002);  // 0.23, 0.17, 0.11 deg/s
    const Trajectory t = circle(20.0, 3.0);
    const Run run = simulate(t, noise, kTestDatum, 90.0, 5);
    PoseEstimator est(matched_config(noise));
    const std::vector<PoseEstimate> poses = run_all(est, run.inputs);
    REQUIRE(!poses.empty());
    const PoseEstimate& last = poses.back();
    INFO("estimated bias " << last.gyro_bias.transpose());
    CHECK((last.gyro_bias - noise.gyro_bias_rps).cwiseAbs().maxCoeff() < 0.001);
    TiltScore s;
    for (const PoseEstimate& p : poses) {
        if (seconds(run, p.utime) > 30.0) {
            add(s, p.orientation, truth_at(t, run, p.utime));
        }
    }
    finish(s);
    CHECK(s.rms < 0.3 * kDeg);
}

TEST_CASE("a steady turn with an AHRS's false tilt: roll and pitch within 0.3 deg RMS, 1 deg max")
{
    // 5 m/s on a 50 m radius: 0.5 m/s^2 sideways, which the AHRS (time constant 10 s) takes for
    // ~2 deg of tilt; its gyros are biased too.
    Noise noise = quiet_imu();
    noise.ahrs_time_constant_s = 10.0;
    noise.imu_orientation_sigma_rad = 0.001;
    noise.gyro_bias_rps = Eigen::Vector3d(0.002, -0.002, 0.001);
    const Trajectory t = circle(50.0, 5.0);
    const Run run = simulate(t, noise, kTestDatum, 90.0, 11);
    PoseEstimator est(matched_config(noise));
    const std::vector<PoseEstimate> poses = run_all(est, run.inputs);
    TiltScore ahrs, ours;
    for (const Input& in : run.inputs) {
        const auto* s = std::get_if<ImuSample>(&in);
        if (s && seconds(run, s->utime) > 30.0) {
            const Eigen::Quaterniond level_yaw(Eigen::AngleAxisd(-noise.heading_offset_rad, Eigen::Vector3d::UnitZ()));
            add(ahrs, level_yaw * s->orientation, truth_at(t, run, s->utime));
        }
    }
    for (const PoseEstimate& p : poses) {
        if (seconds(run, p.utime) > 30.0) {
            add(ours, p.orientation, truth_at(t, run, p.utime));
        }
    }
    finish(ahrs);
    finish(ours);
    INFO("AHRS tilt error RMS " << ahrs.rms / kDeg << " max " << ahrs.max / kDeg << " deg; ours RMS "
                                << ours.rms / kDeg << " max " << ours.max / kDeg << " deg");
    CHECK(ahrs.rms > 1.5 * kDeg);  // the input is as wrong as the test says
    CHECK(ours.rms < 0.3 * kDeg);
    CHECK(ours.max < 1.0 * kDeg);
}

TEST_CASE("a compass error that changes with the heading: the yaw follows the course and the gyros")
{
    // 3 deg of deviation on a circle: the IMU's yaw error swings +-3 deg over one lap (42 s),
    // too fast for the heading offset to follow. Taken as independent 50 Hz samples it outweighs
    // the GPS course; as evidence correlated over 10 s it does not.
    Noise noise = quiet_imu();
    noise.compass_deviation_rad = 3.0 * kDeg;
    noise.imu_orientation_sigma_rad = 0.035;  // the GX1's dynamic accuracy, as its driver reports
    const Trajectory t = circle(20.0, 3.0);
    const Run run = simulate(t, noise, kTestDatum, 90.0, 13);
    auto yaw_rms = [&](double yaw_time_constant_s) {
        EstimatorConfig c = matched_config(noise);
        c.imu_yaw_time_constant_s = yaw_time_constant_s;
        PoseEstimator est(c);
        double sum = 0.0;
        int n = 0;
        for (const PoseEstimate& p : run_all(est, run.inputs)) {
            if (seconds(run, p.utime) > 30.0) {
                const double e = ugv::geometry::wrap_angle(p.yaw - truth_at(t, run, p.utime).yaw);
                sum += e * e;
                ++n;
            }
        }
        REQUIRE(n > 0);
        return std::sqrt(sum / n);
    };
    const double independent = yaw_rms(0.0), correlated = yaw_rms(10.0);
    INFO("yaw error RMS: samples independent " << independent / kDeg << " deg, correlated over 10 s "
                                               << correlated / kDeg << " deg");
    CHECK(independent > 0.8 * kDeg);
    CHECK(correlated < 0.5 * kDeg);
}
