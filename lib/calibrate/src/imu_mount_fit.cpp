#include "ugv/calibrate/imu_mount_fit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include <Eigen/Geometry>

#include "ugv/geometry/rotation.hpp"

namespace ugv::calibrate {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// Samples closer than this belong to one still period or one acceleration event.
constexpr double kGapS = 0.5;

// The kinematic acceleration: the specific force less gravity along the unit's own "up".
Eigen::Vector3d kinematic(const ImuMountSample& m, double gravity) { return m.accel_mps2 - gravity * m.up; }

// Still: quiet rates, a steady specific force, and (with the unit's "up") no horizontal
// acceleration, so a constant acceleration, as steady as standing, is not taken for gravity.
std::vector<bool> still_samples(const std::vector<ImuMountSample>& s, const ImuMountFitConfig& c)
{
    constexpr double kNominalGravity = 9.80665;
    std::vector<bool> still(s.size(), false);
    std::size_t lo = 0, hi = 0;
    for (std::size_t i = 0; i < s.size(); ++i) {
        while (s[lo].t_s < s[i].t_s - c.still_window_s / 2) ++lo;
        while (hi < s.size() && s[hi].t_s <= s[i].t_s + c.still_window_s / 2) ++hi;
        Eigen::Vector3d mean = Eigen::Vector3d::Zero(), moving = Eigen::Vector3d::Zero();
        int with_up = 0;
        bool quiet = true;
        for (std::size_t k = lo; k < hi; ++k) {
            mean += s[k].accel_mps2;
            quiet = quiet && s[k].rate_radps.cwiseAbs().maxCoeff() < c.still_rate_radps;
            if (s[k].has_up) {  // horizontal only: the accelerometer's scale stays out of it
                const Eigen::Vector3d a = kinematic(s[k], kNominalGravity);
                moving += a - a.dot(s[k].up) * s[k].up;
                ++with_up;
            }
        }
        if (!quiet || hi - lo < 3 || (with_up > 0 && (moving / with_up).norm() >= c.still_kinematic_mps2)) continue;
        mean /= static_cast<double>(hi - lo);
        bool steady = true;
        for (std::size_t k = lo; k < hi && steady; ++k)
            steady = (s[k].accel_mps2 - mean).norm() < c.still_accel_spread_mps2;
        still[i] = steady;
    }
    return still;
}

// The spread of per-group estimates (1-sigma of their mean), 0 with fewer than two groups.
double spread_of_mean(const std::vector<double>& v)
{
    if (v.size() < 2) return 0;
    double m = 0, ss = 0;
    for (double x : v) m += x / static_cast<double>(v.size());
    for (double x : v) ss += (x - m) * (x - m);
    return std::sqrt(ss / static_cast<double>(v.size() - 1) / static_cast<double>(v.size()));
}

}  // namespace

ImuMountFitResult fit_imu_mount(const std::vector<ImuMountSample>& s, const Eigen::Vector3d& configured,
                                const ImuMountFitConfig& c)
{
    ImuMountFitResult r;
    for (int k = 0; k < kImuAngles; ++k) {
        ParamEstimate& p = r.params[static_cast<std::size_t>(k)];
        p.initial = p.value = configured[k];
        p.sigma = INFINITY;
    }
    if (s.size() >= 2) r.span_s = s.back().t_s - s.front().t_s;
    if (r.span_s < c.min_still_s) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "too short: %.1f s of IMU samples, at least %.1f s still and then driving",
                      r.span_s, c.min_still_s);
        r.failure = buf;
        return r;
    }

    // Gravity: the mean specific force while still, and its spread over the still periods.
    const std::vector<bool> still = still_samples(s, c);
    Eigen::Vector3d sum = Eigen::Vector3d::Zero(), sum_sq = Eigen::Vector3d::Zero();
    std::size_t n_still = 0;
    std::vector<Eigen::Vector3d> period_sums;
    double period_start = 0, last_still = -1e300;
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (!still[i]) continue;
        if (s[i].t_s - last_still > kGapS) {
            if (!period_sums.empty()) r.still_s += last_still - period_start;
            period_sums.emplace_back(Eigen::Vector3d::Zero());
            period_start = s[i].t_s;
        }
        last_still = s[i].t_s;
        period_sums.back() += s[i].accel_mps2;
        sum += s[i].accel_mps2;
        sum_sq += s[i].accel_mps2.cwiseAbs2();
        ++n_still;
    }
    if (!period_sums.empty()) r.still_s += last_still - period_start;
    r.still_periods = static_cast<int>(period_sums.size());
    if (r.still_s < c.min_still_s) {
        char buf[200];
        std::snprintf(buf, sizeof buf, "no static period: %.1f s still (rates below %.2f rad/s, specific force steady "
                      "within %.2f m/s^2), at least %.1f s (stand still on level ground first)",
                      r.still_s, c.still_rate_radps, c.still_accel_spread_mps2, c.min_still_s);
        r.failure = buf;
        return r;
    }
    const double n = static_cast<double>(n_still);
    r.gravity_mps2 = sum.norm() / n;
    const Eigen::Vector3d up = sum.normalized();
    const Eigen::Vector3d noise = (sum_sq / n - (sum / n).cwiseAbs2()).cwiseMax(0.0).cwiseSqrt();
    std::vector<double> px, py;
    for (const Eigen::Vector3d& p : period_sums) {
        const Eigen::Vector3d u = p.normalized();
        px.push_back(u.x());
        py.push_back(u.y());
    }
    // up ~ (pitch, -roll, 1) for a small residual.
    const double sigma_pitch = std::max(noise.x() / r.gravity_mps2 / std::sqrt(n), spread_of_mean(px));
    const double sigma_roll = std::max(noise.y() / r.gravity_mps2 / std::sqrt(n), spread_of_mean(py));

    // Yaw: the direction of straight-line acceleration around "up". The unit's attitude
    // leans toward its specific force while the vehicle accelerates or turns (its filter's
    // false tilt) and leans back slowly: each event is taken against the mean before and
    // after it (interpolated), so a lean left over from a turn does not turn the direction.
    const Eigen::Vector3d e1 = (Eigen::Vector3d::UnitX() - up.x() * up).normalized();
    const Eigen::Vector3d e2 = up.cross(e1);
    struct Horizontal
    {
        double t;
        Eigen::Vector2d h;
    };
    std::vector<Horizontal> straight;
    for (const ImuMountSample& m : s) {
        if (!m.has_up || std::abs(m.rate_radps.z()) >= c.straight_rate_radps) continue;
        const Eigen::Vector3d k = kinematic(m, r.gravity_mps2);
        straight.push_back({m.t_s, {k.dot(e1), k.dot(e2)}});
    }
    std::vector<std::pair<std::size_t, std::size_t>> events;  // [first, last] in straight
    for (std::size_t i = 0; i < straight.size(); ++i) {
        if (straight[i].h.norm() < c.min_accel_mps2) continue;
        if (events.empty() || straight[i].t - straight[events.back().second].t > kGapS) events.push_back({i, i});
        events.back().second = i;
    }
    auto quiet_mean = [&](double from, double to, Eigen::Vector2d& mean) {
        mean.setZero();
        int n_quiet = 0;
        for (const Horizontal& q : straight)
            if (q.t >= from && q.t <= to && q.h.norm() < c.min_accel_mps2) {
                mean += q.h;
                ++n_quiet;
            }
        if (n_quiet > 0) mean /= n_quiet;
        return n_quiet > 0;
    };
    constexpr double kBaselineS = 1.5, kGuardS = 0.2;
    std::vector<Eigen::Vector2d> acc;
    std::vector<int> event_of;
    for (const auto& [first, last] : events) {
        const double t0 = straight[first].t, t1 = straight[last].t;
        Eigen::Vector2d before, after;
        const bool has_before = quiet_mean(t0 - kBaselineS, t0 - kGuardS, before);
        const bool has_after = quiet_mean(t1 + kGuardS, t1 + kBaselineS, after);
        if (!has_before) before = has_after ? after : Eigen::Vector2d::Zero();
        if (!has_after) after = before;
        for (std::size_t i = first; i <= last; ++i) {
            const double f = t1 > t0 ? (straight[i].t - t0) / (t1 - t0) : 0.5;
            const Eigen::Vector2d h = straight[i].h - (before + f * (after - before));
            acc.push_back(h);
            event_of.push_back(r.accel_events);
            r.max_accel_mps2 = std::max(r.max_accel_mps2, h.norm());
        }
        ++r.accel_events;
    }
    r.accel_samples = acc.size();
    if (acc.empty()) {
        char buf[200];
        std::snprintf(buf, sizeof buf, "no motion: no straight acceleration of %.1f m/s^2 or more (drive straight, "
                      "speeding up and braking)", c.min_accel_mps2);
        r.failure = buf;
        return r;
    }
    // The principal direction (sign-free: braking counts as much as speeding up).
    auto principal = [](const std::vector<Eigen::Vector2d>& v, int event, const std::vector<int>& of) {
        double sxx = 0, syy = 0, sxy = 0;
        for (std::size_t i = 0; i < v.size(); ++i) {
            if (event >= 0 && of[i] != event) continue;
            sxx += v[i].x() * v[i].x();
            syy += v[i].y() * v[i].y();
            sxy += v[i].x() * v[i].y();
        }
        return 0.5 * std::atan2(2 * sxy, sxx - syy);
    };
    const double yaw = principal(acc, -1, event_of);
    double along = 0, across = 0;
    for (const Eigen::Vector2d& h : acc) {
        along += std::pow(std::cos(yaw) * h.x() + std::sin(yaw) * h.y(), 2);
        across += std::pow(-std::sin(yaw) * h.x() + std::cos(yaw) * h.y(), 2);
    }
    std::vector<double> per_event;
    for (int e = 0; e < r.accel_events; ++e)
        if (std::count(event_of.begin(), event_of.end(), e) >= 5) per_event.push_back(principal(acc, e, event_of));
    const double sigma_yaw =
        acc.size() < 2 ? INFINITY
                       : std::max(std::sqrt(across / static_cast<double>(acc.size() - 1) / along), spread_of_mean(per_event));

    // D: the true body's axes in the reported frame; the mounting D^T M_c.
    const Eigen::Vector3d x_axis = std::cos(yaw) * e1 + std::sin(yaw) * e2;
    Eigen::Matrix3d d;
    d.col(0) = x_axis;
    d.col(1) = up.cross(x_axis);
    d.col(2) = up;
    const geometry::Euler res = geometry::euler_from_quaternion(Eigen::Quaterniond(d));
    r.residual_rpy_rad = {res.roll, res.pitch, res.yaw};
    const Eigen::Matrix3d mc = geometry::rotation_from_euler({configured.x(), configured.y(), configured.z()});
    const bool yaw_known = acc.size() >= c.min_accel_samples && sigma_yaw <= c.max_sigma_deg * kDeg;
    // Without the yaw, only the tilt is corrected: D's roll and pitch, its yaw left at zero.
    const Eigen::Matrix3d used = yaw_known ? d : geometry::rotation_from_euler({res.roll, res.pitch, 0.0});
    const geometry::Euler mount = geometry::euler_from_quaternion(Eigen::Quaterniond(Eigen::Matrix3d(used.transpose() * mc)));
    const double sigmas[kImuAngles] = {sigma_roll, sigma_pitch, sigma_yaw};
    const double values[kImuAngles] = {mount.roll, mount.pitch, mount.yaw};
    for (int k = 0; k < kImuAngles; ++k) {
        ParamEstimate& p = r.params[static_cast<std::size_t>(k)];
        p.sigma = sigmas[k];
        p.determined = k == kImuYaw ? yaw_known : p.sigma <= c.max_sigma_deg * kDeg;
        p.value = p.determined ? values[k] : p.initial;
    }
    return r;
}

}  // namespace ugv::calibrate
