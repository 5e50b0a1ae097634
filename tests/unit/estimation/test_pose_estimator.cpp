#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "run_helpers.hpp"

using namespace ugv::estimation;
using namespace ugv::estimation::synthetic;

namespace {

double seconds(const Run& run, int64_t utime)
{
    return static_cast<double>(utime - run.start_utime) * 1e-6;
}

struct Score
{
    double rms_horizontal_m = 0.0;
    double max_horizontal_m = 0.0;
    double rms_yaw_rad = 0.0;
    int n = 0;
};

Score score(const std::vector<PoseEstimate>& poses, const Trajectory& t, const Run& run, double from_s, double to_s)
{
    Score s;
    for (const PoseEstimate& p : poses) {
        const double ts = seconds(run, p.utime);
        if (ts < from_s || ts > to_s) {
            continue;
        }
        const PoseError e = error_of(p, truth_at(t, run, p.utime));
        s.rms_horizontal_m += e.position.head<2>().squaredNorm();
        s.max_horizontal_m = std::max(s.max_horizontal_m, e.position.head<2>().norm());
        s.rms_yaw_rad += e.yaw * e.yaw;
        ++s.n;
    }
    REQUIRE(s.n > 0);
    s.rms_horizontal_m = std::sqrt(s.rms_horizontal_m / s.n);
    s.rms_yaw_rad = std::sqrt(s.rms_yaw_rad / s.n);
    return s;
}

bool same_bits(const PoseEstimate& a, const PoseEstimate& b)
{
    const auto eq = [](const auto& x, const auto& y) { return std::memcmp(&x, &y, sizeof(x)) == 0; };
    return a.utime == b.utime && a.status == b.status && eq(a.position, b.position) && eq(a.velocity, b.velocity) &&
           eq(a.orientation.coeffs(), b.orientation.coeffs()) && eq(a.error_covariance, b.error_covariance) &&
           eq(a.heading_offset, b.heading_offset);
}

const PoseEstimate* at(const std::vector<PoseEstimate>& poses, const Run& run, double t_s)
{
    const int64_t u = run.start_utime + static_cast<int64_t>(std::llround(t_s * 1e6));
    for (const PoseEstimate& p : poses) {
        if (p.utime == u) {
            return &p;
        }
    }
    return nullptr;
}

}  // namespace

TEST_CASE("straight line from rest: DEGRADED until moving, then the yaw and its offset converge")
{
    const Noise noise;
    const double heading = 0.5;
    const Trajectory t = straight(heading, 0.5, 3.0);
    const Run run = simulate(t, noise, kTestDatum, 40.0, 1);
    PoseEstimator est(matched_config(noise));
    const auto poses = run_all(est, run.inputs);

    // Standing still at first (below course_min_speed until t = 2 s): heading not observed.
    const PoseEstimate* early = at(poses, run, 1.0);
    REQUIRE(early);
    CHECK(early->status == PoseStatus::degraded);
    CHECK_FALSE(early->heading_observed);
    // Before the course is seen the IMU's magnetic yaw is what the yaw starts from (off by the
    // offset); the direction of the acceleration the GPS velocity sees moves it, within the
    // yaw's own uncertainty.
    const double early_error = ugv::geometry::wrap_angle(early->yaw - heading);
    CHECK(std::fabs(early_error) < 3.0 * std::sqrt(early->orientation_covariance(2, 2)));

    const Score s = score(poses, t, run, 10.0, 40.0);
    CHECK(s.rms_horizontal_m < 0.2);  // GPS alone: 0.5 m per axis
    CHECK(s.rms_yaw_rad < 0.01);
    const PoseEstimate& last = poses.back();
    CHECK(last.status == PoseStatus::ok);
    CHECK(last.heading_observed);
    CHECK(last.heading_offset == Approx(noise.heading_offset_rad).margin(3.0 * last.heading_offset_sigma + 1e-3));
    CHECK(last.heading_offset_sigma < 0.01);
    CHECK(est.counters().gps_rejected == 0);
    CHECK(est.counters().outages == 0);
}

TEST_CASE("circle and figure eight: position and attitude error against the truth")
{
    const Noise noise;
    for (const auto& [name, t] :
         {std::pair{"circle", circle(20.0, 3.0)}, std::pair{"eight", figure_eight(30.0, 0.1)}}) {
        INFO(name);
        const Run run = simulate(t, noise, kTestDatum, 60.0, 2);
        PoseEstimator est(matched_config(noise));
        const auto poses = run_all(est, run.inputs);
        const Score s = score(poses, t, run, 10.0, 60.0);
        CHECK(s.rms_horizontal_m < 0.2);
        CHECK(s.max_horizontal_m < 0.6);
        CHECK(s.rms_yaw_rad < 0.01);
        CHECK(poses.back().status == PoseStatus::ok);
        // Roll and pitch come from the IMU alone (sigma 0.01 rad per sample), so their
        // reported sigma must be well below that after averaging.
        CHECK(std::sqrt(poses.back().orientation_covariance(0, 0)) < 0.01);
        CHECK(std::sqrt(poses.back().orientation_covariance(2, 2)) < 0.01);
    }
}

TEST_CASE("poses come on the 100 ms grid of data time, one per period")
{
    const Noise noise;
    const Run run = simulate(circle(20.0, 3.0), noise, kTestDatum, 10.0, 3);
    PoseEstimator est(matched_config(noise));
    const auto poses = run_all(est, run.inputs);
    REQUIRE(poses.size() == 100);  // first fix at 3 ms, last input at 10.0 s
    for (std::size_t i = 0; i < poses.size(); ++i) {
        CHECK(poses[i].utime % 100'000 == 0);
        if (i > 0) {
            CHECK(poses[i].utime - poses[i - 1].utime == 100'000);
        }
    }
    CHECK(est.counters().poses == 100);
}

TEST_CASE("a 30 m multipath jump is rejected and counted; the pose does not move")
{
    const Noise noise;
    const Trajectory t = circle(20.0, 3.0);
    const Run run = simulate(t, noise, kTestDatum, 40.0, 4);
    const LocalFrame frame(kTestDatum);
    std::vector<Input> inputs = run.inputs;
    int jumped = 0;
    for (Input& in : inputs) {
        if (auto* f = std::get_if<GpsFix>(&in); f && seconds(run, f->utime) >= 20.0 && seconds(run, f->utime) < 21.5) {
            const Eigen::Vector3d enu = frame.to_enu(f->latitude_deg, f->longitude_deg, f->height_m);
            const Eigen::Vector3d llh = frame.to_geodetic(enu + Eigen::Vector3d(30.0, 0.0, 0.0));
            f->latitude_deg = llh.x();
            f->longitude_deg = llh.y();
            ++jumped;
        }
    }
    REQUIRE(jumped == 8);
    // The clean run's own gate rejections (a 0.1 % tail of honest noise) plus the 8 jumped.
    PoseEstimator clean(matched_config(noise));
    run_all(clean, run.inputs);
    PoseEstimator est(matched_config(noise));
    const auto poses = run_all(est, inputs);
    CHECK(est.counters().gps_rejected == clean.counters().gps_rejected + 8);
    CHECK(est.counters().gps_resets == 0);
    const Score s = score(poses, t, run, 19.0, 25.0);
    CHECK(s.max_horizontal_m < 0.6);
    // 1.8 s between the last good fix and the next is longer than gps_timeout (1 s): one outage.
    CHECK(est.counters().outages == 1);
}

TEST_CASE("a 20 s GPS outage: prediction only, covariance grows, DEGRADED, then recovery")
{
    const Noise noise;
    const Trajectory t = circle(20.0, 3.0);
    const Run run = simulate(t, noise, kTestDatum, 60.0, 5);
    std::vector<Input> inputs;
    for (const Input& in : run.inputs) {
        const double ts = seconds(run, utime_of(in));
        if (std::holds_alternative<ImuSample>(in) || ts < 20.0 || ts >= 40.0) {
            inputs.push_back(in);
        }
    }
    PoseEstimator est(matched_config(noise));
    const auto poses = run_all(est, inputs);
    const PoseEstimate* before = at(poses, run, 19.9);
    const PoseEstimate* mid = at(poses, run, 30.0);
    const PoseEstimate* end = at(poses, run, 39.9);
    const PoseEstimate* after = at(poses, run, 50.0);
    REQUIRE((before && mid && end && after));
    CHECK(before->status == PoseStatus::ok);
    CHECK(mid->status == PoseStatus::degraded);
    CHECK(mid->gps_outage);
    CHECK(end->status == PoseStatus::degraded);
    CHECK(after->status == PoseStatus::ok);
    CHECK(est.counters().outages == 1);
    // The covariance grows through the outage.
    CHECK(mid->position_covariance.trace() > 10.0 * before->position_covariance.trace());
    CHECK(end->position_covariance.trace() > 4.0 * mid->position_covariance.trace());
    CHECK(end->velocity_covariance.trace() > mid->velocity_covariance.trace());
    // ... and describes the error: within 3 sigma (per axis) at the end of the outage.
    const PoseError e = error_of(*end, truth_at(t, run, end->utime));
    CHECK(std::fabs(e.position.x()) < 3.0 * std::sqrt(end->position_covariance(0, 0)));
    CHECK(std::fabs(e.position.y()) < 3.0 * std::sqrt(end->position_covariance(1, 1)));
    // Recovery: the first fixes after the outage are accepted (the grown covariance lets
    // them through the gate) and the error is back to normal.
    CHECK(est.counters().gps_rejected == 0);
    const Score s = score(poses, t, run, 45.0, 60.0);
    CHECK(s.rms_horizontal_m < 0.2);
}

TEST_CASE("determinism: the same inputs give bit-identical poses")
{
    const Noise noise;
    const Run run = simulate(figure_eight(30.0, 0.1), noise, kTestDatum, 20.0, 6);
    PoseEstimator a(matched_config(noise)), b(matched_config(noise));
    const auto pa = run_all(a, run.inputs);
    const auto pb = run_all(b, run.inputs);
    REQUIRE(pa.size() == pb.size());
    for (std::size_t i = 0; i < pa.size(); ++i) {
        REQUIRE(same_bits(pa[i], pb[i]));
    }
}

TEST_CASE("inputs out of order within the buffer give the same poses; too late ones are counted")
{
    const Noise noise;
    const Run run = simulate(circle(20.0, 3.0), noise, kTestDatum, 20.0, 7);
    PoseEstimator in_order(matched_config(noise));
    const auto reference = run_all(in_order, run.inputs);

    // Every GPS message delivered 60 ms late (after the IMU samples that followed it):
    // inside the 150 ms buffer.
    std::vector<std::pair<int64_t, Input>> delivery;
    for (const Input& in : run.inputs) {
        const bool gps = !std::holds_alternative<ImuSample>(in);
        delivery.emplace_back(utime_of(in) + (gps ? 60'000 : 0), in);
    }
    std::stable_sort(delivery.begin(), delivery.end(),
                     [](const auto& x, const auto& y) { return x.first < y.first; });
    PoseEstimator shuffled(matched_config(noise));
    for (const auto& [when, in] : delivery) {
        feed(shuffled, in);
    }
    shuffled.flush();
    const auto poses = shuffled.take_poses();
    CHECK(shuffled.counters().reordered > 0);
    CHECK(shuffled.counters().late == 0);
    REQUIRE(poses.size() == reference.size());
    for (std::size_t i = 0; i < poses.size(); ++i) {
        REQUIRE(same_bits(poses[i], reference[i]));
    }

    // One fix 3 s old arriving now (older than the 100 inputs kept) is refused and counted,
    // and changes nothing.
    PoseEstimator late(matched_config(noise));
    int64_t injected_at = 0;
    for (const Input& in : run.inputs) {
        feed(late, in);
        if (injected_at == 0 && seconds(run, utime_of(in)) > 10.0) {
            GpsFix old = std::get<GpsFix>(run.inputs[1]);  // from t = 3 ms
            old.utime = utime_of(in) - 3'000'000;
            late.add(old);
            injected_at = old.utime;
        }
    }
    late.flush();
    CHECK(late.counters().late == 1);
    const auto late_poses = late.take_poses();
    REQUIRE(late_poses.size() == reference.size());
    CHECK(same_bits(late_poses.back(), reference.back()));
}

TEST_CASE("non-finite inputs are refused, counted, and change nothing")
{
    const Noise noise;
    const Run run = simulate(circle(20.0, 3.0), noise, kTestDatum, 10.0, 8);
    PoseEstimator clean(matched_config(noise));
    const auto reference = run_all(clean, run.inputs);

    PoseEstimator dirty(matched_config(noise));
    for (const Input& in : run.inputs) {
        feed(dirty, in);
        if (auto* s = std::get_if<ImuSample>(&in); s && s->utime % 1'000'000 == 0) {
            ImuSample bad = *s;
            bad.accel_mps2.z() = std::numeric_limits<double>::infinity();
            dirty.add(bad);
            GpsFix nan_fix;
            nan_fix.utime = s->utime;
            nan_fix.latitude_deg = std::numeric_limits<double>::quiet_NaN();
            nan_fix.longitude_deg = 0.0;
            nan_fix.height_m = 0.0;
            nan_fix.quality = FixQuality::rtk_fixed;
            dirty.add(nan_fix);
            GpsVelocity nan_vel;
            nan_vel.utime = s->utime;
            nan_vel.horizontal_speed_mps = 1.0;
            dirty.add(nan_vel);  // track NaN
        }
    }
    dirty.flush();
    CHECK(dirty.counters().non_finite == 3 * 11);  // t = 0 .. 10 s
    const auto poses = dirty.take_poses();
    REQUIRE(poses.size() == reference.size());
    CHECK(same_bits(poses.back(), reference.back()));
}

TEST_CASE("datum: configured, or the first fix of the configured quality")
{
    const Noise noise;
    const Run run = simulate(circle(20.0, 3.0), noise, kTestDatum, 5.0, 9);

    SECTION("configured: every pose carries it and positions are relative to it")
    {
        PoseEstimator est(matched_config(noise));
        const auto poses = run_all(est, run.inputs);
        REQUIRE(!poses.empty());
        CHECK(poses.front().datum.latitude_deg == kTestDatum.latitude_deg);
        CHECK(poses.front().datum.longitude_deg == kTestDatum.longitude_deg);
        CHECK(poses.front().datum.height_m == kTestDatum.height_m);
        CHECK(poses.front().position.x() == Approx(20.0).margin(1.5));  // the circle starts at (20, 0)
    }
    SECTION("first fix: the datum is that fix, so the first position is near zero")
    {
        EstimatorConfig c = matched_config(noise);
        c.datum.reset();
        PoseEstimator est(c);
        const auto poses = run_all(est, run.inputs);
        REQUIRE(!poses.empty());
        const GpsFix& first = std::get<GpsFix>(run.inputs[1]);
        CHECK(poses.front().datum.latitude_deg == first.latitude_deg);
        CHECK(poses.front().datum.longitude_deg == first.longitude_deg);
        CHECK(poses.front().datum.height_m == first.height_m);
        CHECK(poses.front().position.head<2>().norm() < 1.5);
    }
    SECTION("first fix of a quality never reached: no datum, no pose")
    {
        EstimatorConfig c = matched_config(noise);
        c.datum.reset();
        c.datum_min_quality = FixQuality::rtk_fixed;  // the synthetic fixes are DGPS
        PoseEstimator est(c);
        CHECK(run_all(est, run.inputs).empty());
        CHECK_FALSE(est.frame().has_value());
        CHECK(est.counters().gps_low_quality == 25);
    }
}

TEST_CASE("fixes below min_fix_quality are not used")
{
    const Noise noise;
    Run run = simulate(circle(20.0, 3.0), noise, kTestDatum, 5.0, 10);
    for (Input& in : run.inputs) {
        if (auto* f = std::get_if<GpsFix>(&in)) {
            f->quality = FixQuality::single;
        }
    }
    EstimatorConfig c = matched_config(noise);
    c.min_fix_quality = FixQuality::dgps;
    PoseEstimator est(c);
    CHECK(run_all(est, run.inputs).empty());
    CHECK(est.counters().gps_low_quality == 25);
    CHECK(est.counters().gps_used == 0);
}

TEST_CASE("invalid configurations are refused")
{
    EstimatorConfig c;
    c.output_period_us = 0;
    CHECK_THROWS_AS(PoseEstimator(c), std::invalid_argument);
    c = EstimatorConfig{};
    c.process.accel = -1.0;
    CHECK_THROWS_AS(PoseEstimator(c), std::invalid_argument);
    c = EstimatorConfig{};
    c.min_fix_quality = FixQuality::none;
    CHECK_THROWS_AS(PoseEstimator(c), std::invalid_argument);
}

// Found by tests/integration/badmsg: the same message delivered twice was applied twice
// (its information counted double, the covariance overconfident) and not counted.
TEST_CASE("an input delivered twice is applied once and counted as a duplicate, buffered or already applied")
{
    const Noise noise;
    const Run run = simulate(circle(20.0, 3.0), noise, kTestDatum, 10.0, 3);
    for (const int64_t buffer_us : {int64_t{150'000}, int64_t{0}}) {
        INFO("buffer_us " << buffer_us);
        EstimatorConfig config = matched_config(noise);
        config.buffer_us = buffer_us;
        PoseEstimator once(config);
        const auto expected = run_all(once, run.inputs);
        PoseEstimator twice(config);
        for (const Input& in : run.inputs) {
            feed(twice, in);
            feed(twice, in);  // with buffer 0 the first copy is already applied
        }
        twice.flush();
        const auto poses = twice.take_poses();
        CHECK(twice.counters().duplicates == static_cast<int64_t>(run.inputs.size()));
        CHECK(twice.counters().late == 0);
        REQUIRE(poses.size() == expected.size());
        for (std::size_t i = 0; i < poses.size(); ++i) {
            CHECK(poses[i].position == expected[i].position);
            CHECK(poses[i].position_covariance == expected[i].position_covariance);
        }
    }
}

TEST_CASE("a gap in the inputs longer than gps_reset_after_us is not predicted across, whatever its length")
{
    const Noise noise;
    const Run run = simulate(circle(20.0, 3.0), noise, kTestDatum, 10.0, 5);
    for (const int64_t gap_us : {int64_t{30'000'000}, int64_t{365} * 86'400'000'000}) {
        INFO("gap " << gap_us << " us");
        PoseEstimator est(matched_config(noise));
        int64_t last = 0;
        for (const Input& in : run.inputs) {
            feed(est, in);
            std::visit([&](const auto& x) { last = std::max(last, x.utime); }, in);
        }
        const std::size_t before = est.take_poses().size();
        REQUIRE(before > 50);
        // The same inputs again, after the gap: the filter restarts from their first fix
        // instead of emitting a pose per period of the gap.
        for (const Input& in : run.inputs) {
            Input shifted = in;
            std::visit([&](auto& x) { x.utime += last - run.start_utime + gap_us; }, shifted);
            feed(est, shifted);
        }
        est.flush();
        const auto after = est.take_poses();
        CHECK(est.counters().input_gaps == 1);
        CHECK(after.size() <= before + 20);
        REQUIRE_FALSE(after.empty());
        // The first run's tail, then the second run: nothing inside the gap.
        const auto in_gap = std::count_if(after.begin(), after.end(), [&](const PoseEstimate& p) {
            return p.utime > last && p.utime <= last + gap_us;
        });
        CHECK(in_gap == 0);
        CHECK(after.back().utime > last + gap_us);
    }
}

namespace {

// The estimator as ugv-pose runs it: no reorder window, a pose after each IMU sample, late
// inputs applied from the history.
EstimatorConfig prompt_config(const Noise& noise)
{
    EstimatorConfig c = matched_config(noise);
    c.buffer_us = 0;
    c.pose_times = PoseTimes::imu;
    c.output_period_us = 10'000;
    c.history_size = 100;
    return c;
}

// The inputs in the order they arrive when each GPS message after the first fix comes its
// delay after its stamp (behind the IMU samples measured meanwhile).
std::vector<Input> gps_delayed(const std::vector<Input>& inputs, int64_t fix_delay_us, int64_t velocity_delay_us)
{
    std::vector<std::pair<int64_t, Input>> delivery;
    bool first_fix = true;
    for (const Input& in : inputs) {
        int64_t delay = 0;
        if (std::holds_alternative<GpsFix>(in)) {
            delay = first_fix ? 0 : fix_delay_us;
            first_fix = false;
        } else if (std::holds_alternative<GpsVelocity>(in)) {
            delay = velocity_delay_us;
        }
        delivery.emplace_back(utime_of(in) + delay, in);
    }
    std::stable_sort(delivery.begin(), delivery.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    std::vector<Input> out;
    for (auto& [when, in] : delivery) out.push_back(std::move(in));
    return out;
}

void check_same_state(const PoseEstimator& a, const PoseEstimator& b)
{
    const NominalState& x = a.filter().state();
    const NominalState& y = b.filter().state();
    CHECK((x.position - y.position).norm() < 1e-9);
    CHECK((x.velocity - y.velocity).norm() < 1e-9);
    CHECK(x.attitude.angularDistance(y.attitude) < 1e-12);
    CHECK(std::fabs(x.heading_offset - y.heading_offset) < 1e-12);
    CHECK((a.filter().covariance() - b.filter().covariance()).cwiseAbs().maxCoeff() < 1e-12);
}

}  // namespace

TEST_CASE("a pose after each IMU sample, on its stamp, as soon as the sample is applied")
{
    const Noise noise;
    const Run run = simulate(circle(20.0, 3.0), noise, kTestDatum, 5.0, 11);
    PoseEstimator est(prompt_config(noise));
    std::size_t imu_after_init = 0;
    for (const Input& in : run.inputs) {
        feed(est, in);
        if (const auto* s = std::get_if<ImuSample>(&in); s && est.initialized()) {
            // Nothing waits: the pose for this sample is out before the next input comes.
            const auto poses = est.take_poses();
            REQUIRE(poses.size() == 1);
            CHECK(poses.front().utime == s->utime);
            ++imu_after_init;
        }
    }
    CHECK(imu_after_init > 200);  // 50 Hz for ~5 s
    CHECK(est.counters().poses == static_cast<int64_t>(imu_after_init));
}

TEST_CASE("late GPS is applied at its own time: the same final state as delivered in order")
{
    const Noise noise;
    const Run run = simulate(figure_eight(30.0, 0.1), noise, kTestDatum, 20.0, 12);
    PoseEstimator in_order(prompt_config(noise));
    run_all(in_order, run.inputs);
    REQUIRE(in_order.counters().reordered == 0);

    // Fixes 100 ms late, velocities 340 ms late (a NovAtel at 9600 baud): behind 5 and 17
    // IMU samples.
    const std::vector<Input> late_inputs = gps_delayed(run.inputs, 100'000, 340'000);
    PoseEstimator late(prompt_config(noise));
    const auto poses = run_all(late, late_inputs);
    CHECK(late.counters().reordered == 199);  // every fix and velocity after the first fix
    CHECK(late.counters().late == 0);
    CHECK(late.counters().gps_used == in_order.counters().gps_used);
    CHECK(late.counters().velocity_used == in_order.counters().velocity_used);
    CHECK(late.counters().imu_used == in_order.counters().imu_used);
    CHECK(late.counters().poses == in_order.counters().poses);
    check_same_state(late, in_order);
    // Poses are not revised: one per IMU sample, in time order.
    for (std::size_t i = 1; i < poses.size(); ++i) {
        REQUIRE(poses[i].utime > poses[i - 1].utime);
    }

    // Without a history the same delivery loses every GPS message.
    EstimatorConfig no_history = prompt_config(noise);
    no_history.history_size = 0;
    PoseEstimator dropped(no_history);
    run_all(dropped, late_inputs);
    CHECK(dropped.counters().late == 199);
    CHECK((dropped.filter().state().position - in_order.filter().state().position).norm() > 1e-3);
}

TEST_CASE("an input older than the history is dropped and counted; the state is as without it")
{
    const Noise noise;
    const Run run = simulate(circle(20.0, 3.0), noise, kTestDatum, 10.0, 13);
    EstimatorConfig c = prompt_config(noise);
    c.history_size = 20;  // 20 inputs: ~0.33 s at 50 Hz IMU and 2 x 5 Hz GPS
    PoseEstimator without(c);
    run_all(without, run.inputs);

    PoseEstimator est(c);
    bool injected = false;
    for (const Input& in : run.inputs) {
        feed(est, in);
        if (!injected && utime_of(in) - run.start_utime > 5'000'000) {
            GpsFix old = std::get<GpsFix>(run.inputs[1]);
            old.utime = utime_of(in) - 500'000;  // behind 30 inputs
            est.add(old);
            injected = true;
        }
    }
    est.flush();
    CHECK(est.counters().late == 1);
    CHECK(est.counters().reordered == 0);
    check_same_state(est, without);

    // An input delivered twice, the second copy late: applied once.
    PoseEstimator twice(c);
    const Input* previous_fix = nullptr;
    for (const Input& in : run.inputs) {
        feed(twice, in);
        if (std::holds_alternative<ImuSample>(in) && previous_fix) {
            feed(twice, *previous_fix);
            previous_fix = nullptr;
        } else if (std::holds_alternative<GpsFix>(in)) {
            previous_fix = &in;
        }
    }
    twice.flush();
    CHECK(twice.counters().duplicates == 50);
    check_same_state(twice, without);
}

TEST_CASE("an input stamped far ahead of the newest is refused and counted; a gap in every input is not")
{
    const Noise noise;
    const Run run = simulate(circle(20.0, 3.0), noise, kTestDatum, 10.0, 14);
    const EstimatorConfig c = prompt_config(noise);  // max_ahead_us 0.5 s
    PoseEstimator clean(c);
    const auto reference = run_all(clean, run.inputs);

    for (const int64_t ahead_us : {int64_t{600'000}, int64_t{3'600'000'000}, int64_t{1} << 61}) {
        INFO("ahead " << ahead_us << " us");
        PoseEstimator est(c);
        int injected = 0;
        for (const Input& in : run.inputs) {
            feed(est, in);
            // Once a second, one fix stamped ahead: taken, it would move the filter (and every
            // pose) there, and every input after it would be late.
            if (std::holds_alternative<ImuSample>(in) && utime_of(in) % 1'000'000 < 20'000) {
                GpsFix bad = std::get<GpsFix>(run.inputs[1]);
                bad.utime = utime_of(in) + ahead_us;
                est.add(bad);
                ++injected;
            }
        }
        est.flush();
        const auto poses = est.take_poses();
        REQUIRE(injected >= 9);
        CHECK(est.counters().ahead == injected);
        CHECK(est.counters().late == 0);
        REQUIRE(poses.size() == reference.size());
        CHECK(same_bits(poses.back(), reference.back()));
    }

    // Every input resumes 2 s later (shorter than gps_reset_after): the first is refused, the
    // next agrees with it and is taken, and poses go on.
    PoseEstimator gap(c);
    int64_t last = 0;
    for (const Input& in : run.inputs) {
        if (utime_of(in) - run.start_utime >= 5'000'000) {
            Input shifted = in;
            std::visit([](auto& x) { x.utime += 2'000'000; }, shifted);
            feed(gap, shifted);
        } else {
            feed(gap, in);
        }
        last = std::max(last, utime_of(in) + 2'000'000);
    }
    gap.flush();
    const auto poses = gap.take_poses();
    CHECK(gap.counters().ahead == 1);
    CHECK(gap.counters().input_gaps == 0);
    REQUIRE_FALSE(poses.empty());
    CHECK(poses.back().utime > last - 50'000);
}
