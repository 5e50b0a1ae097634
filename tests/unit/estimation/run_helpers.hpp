// Feeding a synthetic run through a PoseEstimator and scoring its poses against the truth.
// Test support only.
#pragma once

#include <cmath>
#include <vector>

#include "synthetic.hpp"
#include "ugv/estimation/pose_estimator.hpp"
#include "ugv/geometry/rotation.hpp"

namespace ugv::estimation::synthetic {

inline const Datum kTestDatum{50.2700, -110.7400, 750.0};

// The estimator tuned to the synthetic sensors' true noise.
inline EstimatorConfig matched_config(const Noise& n)
{
    EstimatorConfig c;
    c.datum = kTestDatum;
    c.process.accel = n.accel_density;
    c.process.gyro = n.gyro_density;
    c.process.heading_offset = 1e-4;
    c.gps_velocity_sigma_mps = n.gps_velocity_sigma_mps;
    return c;
}

inline void feed(PoseEstimator& est, const Input& in)
{
    std::visit([&](const auto& x) { est.add(x); }, in);
}

inline std::vector<PoseEstimate> run_all(PoseEstimator& est, const std::vector<Input>& inputs)
{
    for (const Input& in : inputs) {
        feed(est, in);
    }
    est.flush();
    return est.take_poses();
}

struct PoseError
{
    Eigen::Vector3d position;
    Eigen::Vector3d velocity;
    Eigen::Vector3d attitude;  // world rotation vector, truth relative to estimate
    double yaw = 0.0;
};

inline PoseError error_of(const PoseEstimate& p, const Truth& t)
{
    PoseError e;
    e.position = t.position - p.position;
    e.velocity = t.velocity - p.velocity;
    e.attitude = geometry::quaternion_log(t.attitude() * p.orientation.conjugate());
    e.yaw = geometry::wrap_angle(t.yaw - p.yaw);
    return e;
}

}  // namespace ugv::estimation::synthetic
