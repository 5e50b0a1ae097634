#include "ugv/calibrate/laser_mount_fit.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

namespace ugv::calibrate {

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// A beam's point on the tilt frame's axes, turned by its tilt: p_body = R_axis q + t_axis.
struct Ray
{
    double qx, qy, qz;
    int32_t block;
};

// Body-frame height of the ray's point for axis roll r, pitch p, height h: the last row of
// R_axis = Rz(yaw) Ry(p) Rx(r) is (-sin p, cos p sin r, cos p cos r), without yaw.
double height(const Ray& q, double r, double p, double h)
{
    return -std::sin(p) * q.qx + std::cos(p) * std::sin(r) * q.qy + std::cos(p) * std::cos(r) * q.qz + h;
}

// d height / d (roll, pitch, yaw, height).
Eigen::Vector4d jacobian(const Ray& q, double r, double p)
{
    const double sr = std::sin(r), cr = std::cos(r), sp = std::sin(p), cp = std::cos(p);
    return {cp * cr * q.qy - cp * sr * q.qz, -cp * q.qx - sp * sr * q.qy - sp * cr * q.qz, 0.0, 1.0};
}

double median_of(std::vector<double>& v)
{
    if (v.empty()) return 0.0;
    const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    return *mid;
}

struct Step
{
    Eigen::Matrix4d h = Eigen::Matrix4d::Zero();  // J^T J over the gated rays
    Eigen::Vector4d g = Eigen::Vector4d::Zero();  // J^T residual
    double sum_sq = 0;
    std::size_t n = 0;
};

// The normal equations over the rays within the gate (of one block, or all with block < 0).
Step normal_equations(const std::vector<Ray>& rays, const Eigen::Vector4d& x, double gate, int block)
{
    Step s;
    for (const Ray& q : rays) {
        if (block >= 0 && q.block != block) continue;
        const double res = height(q, x[kRoll], x[kPitch], x[kHeight]);
        if (!(std::abs(res) <= gate)) continue;
        // Tukey's weight: a beam near the gate (a box's top, a wall's foot) pulls little.
        const double u = res / gate, w = (1 - u * u) * (1 - u * u);
        const Eigen::Vector4d j = jacobian(q, x[kRoll], x[kPitch]);
        s.h.noalias() += w * j * j.transpose();
        s.g += w * j * res;
        s.sum_sq += res * res;
        ++s.n;
    }
    return s;
}

// Gauss-Newton's step for the free parameters; the others stay.
Eigen::Vector4d solve(const Step& s, const std::array<bool, kLaserParams>& free)
{
    Eigen::Matrix4d h = s.h;
    Eigen::Vector4d g = s.g;
    for (int k = 0; k < kLaserParams; ++k) {
        if (free[static_cast<std::size_t>(k)]) continue;
        h.row(k).setZero();
        h.col(k).setZero();
        h(k, k) = 1.0;
        g[k] = 0.0;
    }
    return -h.ldlt().solve(g);
}

double limit_of(int k, const LaserFitConfig& c)
{
    return k == kHeight ? c.max_sigma_height_m : c.max_sigma_angle_deg * kDeg;
}

}  // namespace

const char* laser_param_name(LaserParam p)
{
    static const char* const names[] = {"roll", "pitch", "yaw", "height"};
    return p >= 0 && p < kLaserParams ? names[p] : "?";
}

LaserFitResult fit_laser_mount(const std::vector<LaserBeam>& beams, const nodscan::MountGeometry& initial,
                               const LaserFitConfig& c)
{
    LaserFitResult out;
    out.mount = initial;
    const Eigen::Vector4d x0(initial.axis_rpy_rad.x(), initial.axis_rpy_rad.y(), initial.axis_rpy_rad.z(),
                             initial.axis_xyz_m.z());
    for (int k = 0; k < kLaserParams; ++k) out.params[static_cast<std::size_t>(k)].initial = out.params[static_cast<std::size_t>(k)].value = x0[k];

    // The rays: each beam in the tilt frame (the laser as configured on the axis), turned by
    // its tilt. The axis's x and y offsets do not move a height.
    const Eigen::Matrix3d r_laser = nodscan::rotation_rpy(initial.laser_rpy_rad);
    std::vector<Ray> rays;
    rays.reserve(beams.size());
    float tilt_min = INFINITY, tilt_max = -INFINITY;
    int32_t last_block = 0;
    for (const LaserBeam& b : beams) {
        if (!(b.range_m >= c.min_range_m && b.range_m <= c.max_range_m) || !std::isfinite(b.beam_angle_rad) ||
            !std::isfinite(b.tilt_rad))
            continue;
        const Eigen::Vector3d p = r_laser * Eigen::Vector3d(b.range_m * std::cos(b.beam_angle_rad),
                                                            b.range_m * std::sin(b.beam_angle_rad), 0.0) +
                                  initial.laser_xyz_m;
        const Eigen::Vector3d q = nodscan::tilt_rotation(b.tilt_rad) * p;
        rays.push_back({q.x(), q.y(), q.z(), b.block});
        tilt_min = std::min(tilt_min, b.tilt_rad);
        tilt_max = std::max(tilt_max, b.tilt_rad);
        last_block = std::max(last_block, b.block);
    }
    out.beams = rays.size();
    out.tilt_span_deg = rays.empty() ? 0.0 : (tilt_max - tilt_min) / kDeg;
    char why[200];
    if (rays.size() < c.min_beams) {
        std::snprintf(why, sizeof why, "too few beams between %.1f and %.1f m: %zu (need %zu): record longer",
                      c.min_range_m, c.max_range_m, rays.size(), c.min_beams);
        out.failure = why;
        return out;
    }
    if (out.tilt_span_deg < c.min_tilt_span_deg) {
        std::snprintf(why, sizeof why, "the laser did not nod: tilt span %.1f deg (need %.1f)", out.tilt_span_deg,
                      c.min_tilt_span_deg);
        out.failure = why;
        return out;
    }

    // Gauss-Newton, weighted, within a gate that shrinks to gate_sigmas robust sigmas of the
    // residuals.
    std::array<bool, kLaserParams> free{true, true, true, true};
    Eigen::Vector4d x = x0;
    double gate = c.first_gate_m;
    std::vector<double> abs_res;
    abs_res.reserve(rays.size());
    auto gated_abs_residuals = [&](const Eigen::Vector4d& at, double g) {
        abs_res.clear();
        for (const Ray& q : rays) {
            const double r = std::abs(height(q, at[kRoll], at[kPitch], at[kHeight]));
            if (r <= g) abs_res.push_back(r);
        }
    };
    gated_abs_residuals(x0, gate);
    {
        double s = 0;
        for (double r : abs_res) s += r * r;
        out.rms_before_m = abs_res.empty() ? 0.0 : std::sqrt(s / static_cast<double>(abs_res.size()));
    }
    bool converged = false;
    for (int pass = 0; pass < 2 && !converged; ++pass) {
        // The second pass only if the first found a parameter it cannot determine: fitted again
        // without it.
        for (out.iterations = 0; out.iterations < c.max_iterations; ++out.iterations) {
            const Step s = normal_equations(rays, x, gate, -1);
            if (s.n < 4) break;
            // Parameters the gated rays say nothing about (yaw, always) stay where they are.
            for (int k = 0; k < kLaserParams; ++k)
                if (s.h(k, k) <= 1e-12 * s.h.trace()) free[static_cast<std::size_t>(k)] = false;
            const Eigen::Vector4d dx = solve(s, free);
            x += dx;
            gated_abs_residuals(x, gate);
            // 1.4826 MAD of |r| about 0: the ground's residuals are centred there once fitted.
            const double sigma = 1.4826 * median_of(abs_res);
            // Towards gate_sigmas robust sigmas, at most halving at a time so that the fit follows.
            const double target = std::max(c.min_gate_m, c.gate_sigmas * sigma);
            const double next_gate = target < gate ? std::max(target, 0.5 * gate) : gate;
            const bool small = std::abs(dx[kRoll]) < 1e-7 && std::abs(dx[kPitch]) < 1e-7 && std::abs(dx[kHeight]) < 1e-6;
            if (small && next_gate >= gate * 0.999) {
                converged = true;
                break;
            }
            gate = next_gate;
        }
        if (!converged) break;
        // Formal sigmas from the normal equations at the solution; the spread over blocks.
        const Step s = normal_equations(rays, x, gate, -1);
        out.ground_beams = s.n;
        out.gate_m = gate;
        const double var = s.n > kLaserParams ? s.sum_sq / static_cast<double>(s.n - kLaserParams) : 0.0;
        out.rms_after_m = s.n > 0 ? std::sqrt(s.sum_sq / static_cast<double>(s.n)) : 0.0;
        Eigen::Matrix4d h = s.h;
        for (int k = 0; k < kLaserParams; ++k)
            if (!free[static_cast<std::size_t>(k)]) {
                h.row(k).setZero();
                h.col(k).setZero();
                h(k, k) = 1.0;
            }
        const Eigen::Matrix4d cov = h.inverse() * var;
        std::vector<Eigen::Vector4d> per_block;
        for (int32_t b = 0; b <= last_block; ++b) {
            Eigen::Vector4d xb = x;
            bool ok = true;
            for (int it = 0; it < 3 && ok; ++it) {
                const Step sb = normal_equations(rays, xb, gate, b);
                if (sb.n < c.min_beams / 10) ok = false;
                else xb += solve(sb, free);
            }
            if (ok) per_block.push_back(xb);
        }
        out.blocks = static_cast<int>(per_block.size());
        bool dropped = false;
        for (int k = 0; k < kLaserParams; ++k) {
            ParamEstimate& e = out.params[static_cast<std::size_t>(k)];
            if (!free[static_cast<std::size_t>(k)]) {  // held: its sigma from the pass that let it go, or none
                if (!(e.sigma > 0)) e.sigma = std::numeric_limits<double>::infinity();
                e.determined = false;
                e.value = e.initial;
                continue;
            }
            double spread = 0;
            if (per_block.size() >= 2) {
                double mean = 0, ss = 0;
                for (const auto& xb : per_block) mean += xb[k];
                mean /= static_cast<double>(per_block.size());
                for (const auto& xb : per_block) ss += (xb[k] - mean) * (xb[k] - mean);
                spread = std::sqrt(ss / static_cast<double>(per_block.size() - 1) / static_cast<double>(per_block.size()));
            }
            e.sigma = std::max(std::sqrt(std::max(0.0, cov(k, k))), spread);
            e.determined = e.sigma <= limit_of(k, c);
            if (!e.determined) {
                free[static_cast<std::size_t>(k)] = false;
                dropped = true;
            }
            e.value = e.determined ? x[k] : e.initial;
        }
        if (dropped && pass == 0) {
            x = x0;
            for (int k = 0; k < kLaserParams; ++k)
                if (out.params[static_cast<std::size_t>(k)].determined) x[k] = out.params[static_cast<std::size_t>(k)].value;
            gate = c.first_gate_m;
            converged = false;
            // Determined ones stay free; the undetermined are held at their initial values.
            for (int k = 0; k < kLaserParams; ++k) free[static_cast<std::size_t>(k)] = out.params[static_cast<std::size_t>(k)].determined;
            continue;
        }
    }
    if (!converged) {
        std::snprintf(why, sizeof why, "the fit did not settle in %d iterations: is the ground in view flat?",
                      c.max_iterations);
        out.failure = why;
        return out;
    }
    const double fraction = static_cast<double>(out.ground_beams) / static_cast<double>(out.beams);
    if (fraction < c.min_ground_fraction || out.rms_after_m > c.max_ground_rms_m) {
        std::snprintf(why, sizeof why,
                      "no flat ground in view: %.0f%% of the beams fit a plane, residual RMS %.3f m (need %.0f%% "
                      "and %.3f m)",
                      100.0 * fraction, out.rms_after_m, 100.0 * c.min_ground_fraction, c.max_ground_rms_m);
        out.failure = why;
        return out;
    }
    out.mount.axis_rpy_rad = {out.params[kRoll].value, out.params[kPitch].value, out.params[kYaw].value};
    out.mount.axis_xyz_m.z() = out.params[kHeight].value;
    return out;
}

}  // namespace ugv::calibrate
