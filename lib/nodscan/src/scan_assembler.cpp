#include "ugv/nodscan/scan_assembler.hpp"

#include <algorithm>
#include <cmath>

namespace ugv::nodscan {

void PointCloud::clear()
{
    x.clear();
    y.clear();
    z.clear();
    range.clear();
    variance.clear();
    time_offset.clear();
    beam.clear();
}

ScanAssembler::ScanAssembler(AssemblerConfig config)
    : config_(config),
      r_axis_(rotation_rpy(config.mount.axis_rpy_rad))
{
}

bool ScanView::set_sweeps(const int8_t* order, int count, double period)
{
    if (count < 1 || count > kMaxSweeps || !std::isfinite(period) || period < 0.0) return false;
    std::array<int8_t, kMaxSweeps> of_phase{};
    unsigned seen = 0;
    for (int k = 0; k < count; ++k) {
        const int p = order[k];
        if (p < 0 || p >= count || (seen & (1u << p)) != 0) return false;
        seen |= 1u << p;
        of_phase[static_cast<std::size_t>(p)] = static_cast<int8_t>(k);
    }
    sweeps = count;
    sweep_period = period;
    sweep_of_phase = of_phase;
    return true;
}

double ScanView::span_s() const
{
    double span = 0.0;
    const auto s = static_cast<std::size_t>(sweeps);
    for (std::size_t i = n > s ? n - s : 0; i < n; ++i) span = std::max(span, beam_offset_s(i));
    return span;
}

int64_t ScanAssembler::last_beam_utime(const ScanView& s)
{
    return s.utime + static_cast<int64_t>(std::llround(s.span_s() * 1e6));
}

void ScanAssembler::prepare_directions(const ScanView& s)
{
    if (s.n == cached_n_ && s.angle_min == cached_min_ && s.angle_increment == cached_inc_) return;
    const Eigen::Matrix3d r_laser = rotation_rpy(config_.mount.laser_rpy_rad);
    ux_.resize(s.n);
    uy_.resize(s.n);
    uz_.resize(s.n);
    for (std::size_t i = 0; i < s.n; ++i) {
        const double a = s.angle_min + s.angle_increment * static_cast<double>(i);
        const Eigen::Vector3d u = beam_direction_tilt_frame(r_laser, a);
        ux_[i] = u(0);
        uy_[i] = u(1);
        uz_[i] = u(2);
    }
    cached_n_ = s.n;
    cached_min_ = s.angle_min;
    cached_inc_ = s.angle_increment;
}

AssembleStats ScanAssembler::assemble(const ScanView& s, const ServoHistory& servo, PointCloud& out)
{
    AssembleStats st;
    out.clear();
    out.utime = s.utime;
    prepare_directions(s);
    tilt_.resize(s.n);
    tilt_ok_.resize(s.n);
    // Each sweep's beams are evenly spaced in time: one pass of the servo history per sweep.
    const auto sweeps = static_cast<std::size_t>(std::max(1, s.sweeps));
    phase_tilt_.resize(s.n / sweeps + 1);
    phase_ok_.resize(s.n / sweeps + 1);
    for (std::size_t p = 0; p < sweeps && p < s.n; ++p) {
        const std::size_t count = (s.n - p + sweeps - 1) / sweeps;
        const int64_t t0 = s.utime + static_cast<int64_t>(std::llround(s.beam_offset_s(p) * 1e6));
        servo.angles_at(t0, s.time_increment * 1e6 * static_cast<double>(sweeps), count, config_.max_extrapolation_us,
                        phase_tilt_.data(), phase_ok_.data());
        for (std::size_t j = 0; j < count; ++j) {
            tilt_[p + j * sweeps] = phase_tilt_[j];
            tilt_ok_[p + j * sweeps] = phase_ok_[j];
        }
    }

    const auto origin_tilt = servo.angle_at(s.utime, config_.max_extrapolation_us);
    out.sensor_origin = laser_origin_body(config_.mount, origin_tilt.value_or(0.0));

    for (auto* v : {&out.x, &out.y, &out.z, &out.range, &out.variance, &out.time_offset}) v->reserve(s.n);
    out.beam.reserve(s.n);
    const Eigen::Vector3d& tl = config_.mount.laser_xyz_m;
    const Eigen::Vector3d& ta = config_.mount.axis_xyz_m;
    const Eigen::Matrix3d& ra = r_axis_;
    const double var_r = config_.range_sigma_m * config_.range_sigma_m;
    const double var_a = config_.angle_sigma_rad * config_.angle_sigma_rad;
    const double rmax = s.range_max > 0.0 ? s.range_max : INFINITY;
    for (std::size_t i = 0; i < s.n; ++i) {
        const double r = s.ranges[i];
        if (!(r > 0.0 && r <= rmax)) {  // NaN fails every comparison
            ++st.dropped_invalid;
            continue;
        }
        if (!tilt_ok_[i]) {
            ++st.dropped_no_angle;
            continue;
        }
        // In the tilt frame.
        const double px = r * ux_[i] + tl(0);
        const double py = r * uy_[i] + tl(1);
        const double pz = r * uz_[i] + tl(2);
        // Tilt about +Y.
        const double c = std::cos(tilt_[i]);
        const double sn = std::sin(tilt_[i]);
        const double qx = c * px + sn * pz;
        const double qz = -sn * px + c * pz;
        // Onto the vehicle.
        out.x.push_back(static_cast<float>(ra(0, 0) * qx + ra(0, 1) * py + ra(0, 2) * qz + ta(0)));
        out.y.push_back(static_cast<float>(ra(1, 0) * qx + ra(1, 1) * py + ra(1, 2) * qz + ta(1)));
        out.z.push_back(static_cast<float>(ra(2, 0) * qx + ra(2, 1) * py + ra(2, 2) * qz + ta(2)));
        out.range.push_back(static_cast<float>(r));
        out.variance.push_back(static_cast<float>(var_r + r * r * var_a));
        out.time_offset.push_back(static_cast<float>(s.beam_offset_s(i)));
        out.beam.push_back(static_cast<uint32_t>(i));
    }
    st.points = out.size();
    return st;
}

}  // namespace ugv::nodscan
