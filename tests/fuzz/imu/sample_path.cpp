#include "sample_path.hpp"

#include <cmath>
#include <cstdlib>
#include <numbers>

#include "ugv/microstrain_gx1/protocol.hpp"

namespace ugv::fuzz {
namespace {

void require(bool ok)
{
    if (!ok) std::abort();
}

bool finite(const Eigen::Vector3d& v) { return v.allFinite(); }

}  // namespace

void SamplePath::on_frame(const microstrain_gx1::Frame& f)
{
    using namespace microstrain_gx1;
    require(f.nwords == reply_words(f.command));
    const DeviceSample d = decode_sample(f, gains_);
    require(std::isfinite(d.roll_rad) && std::isfinite(d.pitch_rad) && std::isfinite(d.yaw_rad));
    for (double v : d.quaternion) require(std::isfinite(v));
    for (double v : d.matrix) require(std::isfinite(v));
    for (std::size_t i = 0; i < 3; ++i) {
        require(std::isfinite(d.accel_mps2[i]) && std::isfinite(d.rate_radps[i]) && std::isfinite(d.mag_gauss[i]));
    }
    require(std::isfinite(d.temperature_c));

    const Measurement m = converter_.convert(d);
    require(finite(m.rate_radps) && finite(m.accel_mps2) && finite(m.mag_gauss));
    if (m.has_orientation) {
        const auto& a = m.attitude;
        require(a.q_enu_body.coeffs().allFinite());
        require(std::abs(a.q_enu_body.norm() - 1.0) < 1e-9 && a.q_enu_body.w() >= 0.0);
        require(std::isfinite(a.roll_rad) && std::isfinite(a.pitch_rad) && std::isfinite(a.yaw_rad));
        require(std::abs(a.yaw_rad) <= std::numbers::pi + 1e-12);
    }

    if (d.has_ticks) {
        const int64_t ticks = ticks_.unwrap(f.ticks());
        require(ticks >= last_ticks_);
        last_ticks_ = ticks;
        const int64_t utime = clock_.update(static_cast<double>(ticks) * 6.5536e-3, f.first_byte_utime);
        require(utime <= f.first_byte_utime);
    }
}

}  // namespace ugv::fuzz
