#include "ugv/calibrate/antenna_fit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "ugv/calibrate/linear_fit.hpp"

namespace ugv::calibrate {

namespace {

double wrap(double a) { return std::remainder(a, 2 * std::numbers::pi); }

std::string printed(const char* format, double a, double b = 0, double c = 0)
{
    char buf[200];
    std::snprintf(buf, sizeof buf, format, a, b, c);
    return buf;
}

}  // namespace

std::vector<AntennaSample> antenna_samples(const std::vector<ImuRateSample>& imu,
                                           const std::vector<GpsVelocitySample>& gps, double window_s)
{
    std::vector<AntennaSample> out;
    if (imu.size() < 2) return out;
    // The heading: the yaw rate integrated (trapezoids) at each IMU sample.
    std::vector<double> heading(imu.size(), 0.0);
    for (std::size_t i = 1; i < imu.size(); ++i)
        heading[i] = heading[i - 1] + 0.5 * (imu[i - 1].yaw_rate_radps + imu[i].yaw_rate_radps) * (imu[i].t_s - imu[i - 1].t_s);
    auto before = [&](double t) {
        return std::lower_bound(imu.begin(), imu.end(), t, [](const ImuRateSample& s, double v) { return s.t_s < v; });
    };
    for (const GpsVelocitySample& g : gps) {
        if (g.t_s < imu.front().t_s || g.t_s > imu.back().t_s) continue;
        AntennaSample a;
        a.t_s = g.t_s;
        a.speed_mps = g.speed_mps;
        a.track_enu_rad = g.track_enu_rad;
        auto hi = before(g.t_s);
        const auto k = static_cast<std::size_t>(std::max<std::ptrdiff_t>(1, hi - imu.begin()));
        const double span = imu[k].t_s - imu[k - 1].t_s;
        const double f = span > 0 ? std::clamp((g.t_s - imu[k - 1].t_s) / span, 0.0, 1.0) : 0.0;
        a.heading_rad = heading[k - 1] + f * (heading[k] - heading[k - 1]);
        int n = 0;
        for (auto it = before(g.t_s - window_s); it != imu.end() && it->t_s <= g.t_s + window_s; ++it, ++n) {
            a.yaw_rate_radps += it->yaw_rate_radps;
            a.accel_fwd_mps2 += it->accel_fwd_mps2;
            a.accel_lat_mps2 += it->accel_lat_mps2;
        }
        if (n == 0) continue;
        a.yaw_rate_radps /= n;
        a.accel_fwd_mps2 /= n;
        a.accel_lat_mps2 /= n;
        out.push_back(a);
    }
    return out;
}

AntennaFitResult fit_antenna(const std::vector<AntennaSample>& all, double initial_x_m, double initial_y_m,
                             const AntennaFitConfig& config)
{
    AntennaFitResult r;
    r.x.initial = r.x.value = initial_x_m;
    r.y.initial = r.y.value = initial_y_m;
    r.x.sigma = r.y.sigma = INFINITY;
    std::vector<AntennaSample> s;
    for (const AntennaSample& a : all)
        if (a.speed_mps >= config.min_speed_mps) s.push_back(a);
    if (s.empty()) {
        r.failure = printed("no motion: no GPS velocity of %.1f m/s or more (drive, with turns)", config.min_speed_mps);
        return r;
    }
    if (s.size() < config.min_samples) {
        r.failure = printed("too short: %.0f GPS velocities while moving, at least %.0f (drive for longer)",
                            static_cast<double>(s.size()), static_cast<double>(config.min_samples));
        return r;
    }
    r.samples = s.size();
    double turned = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
        const double w = std::abs(s[i].yaw_rate_radps);
        r.max_yaw_rate_radps = std::max(r.max_yaw_rate_radps, w);
        if (w < config.turn_rate_radps) continue;
        ++r.turning_samples;
        if (i > 0) turned += w * std::min(1.0, s[i].t_s - s[i - 1].t_s);
    }
    r.turn_deg = turned * 180.0 / std::numbers::pi;
    if (r.turn_deg < config.min_turn_deg) {
        r.failure = printed("no turns: %.0f deg turned faster than %.2f rad/s, at least %.0f (drive a 90 deg turn or a "
                            "circle)",
                            r.turn_deg, config.turn_rate_radps, config.min_turn_deg);
        return r;
    }

    // The heading's origin first (a circular mean), then x with the heading's offset, scale
    // and drift, relinearised until the corrections vanish.
    const auto n = static_cast<Eigen::Index>(s.size());
    double t_mean = 0, h_mean = 0, sn = 0, cs = 0;
    for (const AntennaSample& a : s) {
        t_mean += a.t_s / static_cast<double>(n);
        h_mean += a.heading_rad / static_cast<double>(n);
        sn += a.speed_mps * std::sin(a.track_enu_rad - a.heading_rad);
        cs += a.speed_mps * std::cos(a.track_enu_rad - a.heading_rad);
    }
    Eigen::Vector3d heading_model(std::atan2(sn, cs), 0, 0);  // offset, scale, drift
    Eigen::VectorXd v_fwd(n);
    LinearFit lateral;
    for (int iteration = 0; iteration < 4; ++iteration) {
        Eigen::MatrixXd a(n, 4);
        Eigen::VectorXd b(n);
        for (Eigen::Index i = 0; i < n; ++i) {
            const AntennaSample& m = s[static_cast<std::size_t>(i)];
            const double dh = m.heading_rad - h_mean, dt = m.t_s - t_mean;
            const double rel = wrap(m.track_enu_rad - (m.heading_rad + heading_model[0] + heading_model[1] * dh +
                                                       heading_model[2] * dt));
            v_fwd[i] = m.speed_mps * std::cos(rel);
            a.row(i) << m.yaw_rate_radps, v_fwd[i], v_fwd[i] * dh, v_fwd[i] * dt;
            b[i] = m.speed_mps * std::sin(rel);
        }
        lateral = fit_linear(a, b, config.gate_sigmas);
        if (!lateral.ok) {
            r.failure = "the turns cannot be told from a heading error: drive straight before and after turning";
            return r;
        }
        heading_model += lateral.value.tail<3>();
    }
    double turning_speed = 0;
    for (const AntennaSample& m : s)
        if (std::abs(m.yaw_rate_radps) >= config.turn_rate_radps)
            turning_speed += m.speed_mps / static_cast<double>(r.turning_samples);
    r.x.value = lateral.value[0];
    r.x.sigma = std::hypot(lateral.sigma[0], turning_speed * config.stamp_alignment_s);
    r.x.determined = r.x.sigma <= config.max_sigma_m;
    if (!r.x.determined) r.x.value = initial_x_m;
    r.lateral_rms_mps = lateral.rms;
    r.heading_scale = heading_model[1];

    // y from the centripetal acceleration: f_lat - w v_fwd = y w^2 + b + e f_fwd.
    Eigen::MatrixXd a(n, 3);
    Eigen::VectorXd b(n);
    for (Eigen::Index i = 0; i < n; ++i) {
        const AntennaSample& m = s[static_cast<std::size_t>(i)];
        a.row(i) << m.yaw_rate_radps * m.yaw_rate_radps, 1.0, m.accel_fwd_mps2;
        b[i] = m.accel_lat_mps2 - m.yaw_rate_radps * v_fwd[i];
    }
    const LinearFit along = fit_linear(a, b, config.gate_sigmas);
    if (along.ok) {
        r.y.value = along.value[0];
        r.y.sigma = along.sigma[0];
        r.accel_rms_mps2 = along.rms;
    }
    r.y.determined = along.ok && r.y.sigma <= config.max_sigma_m;
    if (!r.y.determined) r.y.value = initial_y_m;
    return r;
}

}  // namespace ugv::calibrate
