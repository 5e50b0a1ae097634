// Cost of one filter step (prediction, each kind of update) and of the whole estimator per
// input on a synthetic 50 Hz IMU + 5 Hz GPS stream. Reported in docs/pose.md, never asserted.
#include <benchmark/benchmark.h>

#include "run_helpers.hpp"

using namespace ugv::estimation;
using namespace ugv::estimation::synthetic;
using Eigen::Matrix3d;
using Eigen::Vector3d;

namespace {

ErrorStateFilter settled_filter()
{
    ErrorStateFilter f;
    ErrorStateFilter::Covariance P = ErrorStateFilter::Covariance::Identity() * 0.01;
    f.reset(NominalState{}, P);
    return f;
}

void BM_Predict(benchmark::State& state)
{
    ErrorStateFilter f = settled_filter();
    const Vector3d rate(0.01, -0.02, 0.15), force(0.3, 0.45, 9.81);
    for (auto _ : state) {
        f.predict(0.02, rate, force, ProcessNoise{});
        benchmark::DoNotOptimize(f.covariance().data());
    }
}
BENCHMARK(BM_Predict);

void BM_UpdatePosition(benchmark::State& state)
{
    ErrorStateFilter f = settled_filter();
    const Matrix3d R = Matrix3d::Identity() * 0.25;
    for (auto _ : state) {
        const UpdateResult r = f.update_position(Vector3d(0.01, -0.01, 0.0), R, Vector3d(0.5, 0.0, 1.0), 1e9);
        benchmark::DoNotOptimize(r);
        f.predict(0.02, Vector3d::Zero(), Vector3d(0, 0, 9.80665), ProcessNoise{});  // keep P from collapsing
    }
}
BENCHMARK(BM_UpdatePosition);

void BM_UpdateImuOrientation(benchmark::State& state)
{
    ErrorStateFilter f = settled_filter();
    const Eigen::Quaterniond q(Eigen::AngleAxisd(0.001, Vector3d::UnitZ()));
    const Matrix3d R = Matrix3d::Identity() * 1e-4;
    for (auto _ : state) {
        const UpdateResult r = f.update_imu_orientation(q, R, 1e9);
        benchmark::DoNotOptimize(r);
        f.predict(0.02, Vector3d::Zero(), Vector3d(0, 0, 9.80665), ProcessNoise{});
    }
}
BENCHMARK(BM_UpdateImuOrientation);

// The whole estimator: buffer, prediction, update and pose output, per input message.
void BM_EstimatorPerInput(benchmark::State& state)
{
    const Noise noise;
    const Run run = simulate(circle(20.0, 3.0), noise, kTestDatum, 60.0, 1);
    std::size_t n = 0;
    for (auto _ : state) {
        PoseEstimator est(matched_config(noise));
        for (const Input& in : run.inputs) {
            feed(est, in);
        }
        benchmark::DoNotOptimize(est.take_poses());
        n += run.inputs.size();
    }
    state.counters["per_input"] = benchmark::Counter(static_cast<double>(n), benchmark::Counter::kIsRate |
                                                                               benchmark::Counter::kInvert);
}
BENCHMARK(BM_EstimatorPerInput)->Unit(benchmark::kMillisecond);

}  // namespace
