#include "lms_messages.hpp"

namespace ugv::lms_daemon {

namespace lms = ugv::sick_lms2xx;

// The codec's flag codes are laser_scan_t's, by construction; keep them in step.
static_assert(static_cast<int8_t>(lms::BeamFlag::ok) == ugv::laser_scan_t::FLAG_OK);
static_assert(static_cast<int8_t>(lms::BeamFlag::invalid) == ugv::laser_scan_t::FLAG_INVALID);
static_assert(static_cast<int8_t>(lms::BeamFlag::dazzle) == ugv::laser_scan_t::FLAG_DAZZLE);
static_assert(static_cast<int8_t>(lms::BeamFlag::overflow) == ugv::laser_scan_t::FLAG_OVERFLOW);
static_assert(static_cast<int8_t>(lms::BeamFlag::low_signal) == ugv::laser_scan_t::FLAG_LOW_SIGNAL);
static_assert(static_cast<int8_t>(lms::BeamFlag::error) == ugv::laser_scan_t::FLAG_ERROR);
static_assert(static_cast<int8_t>(lms::BeamFlag::other) == ugv::laser_scan_t::FLAG_OTHER);

ugv::laser_scan_t to_message(const lms::StampedScan& s, const std::string& sensor_id, int64_t seq)
{
    ugv::laser_scan_t m;
    m.utime = s.first_beam_utime;
    m.seq = seq;
    m.sensor_id = sensor_id;
    m.angle_min = static_cast<float>(s.angle_min_rad);
    m.angle_increment = static_cast<float>(s.angle_increment_rad);
    m.time_increment = static_cast<float>(s.time_increment_s);
    m.scan_period = static_cast<float>(s.scan_period_s);
    m.range_max = static_cast<float>(s.range_max_m);
    m.device_scan_counter = s.scan.scan_index;
    m.nsweeps = static_cast<int8_t>(s.sweep_order.sweeps);
    m.sweep_order.assign(s.sweep_order.order.begin(), s.sweep_order.order.begin() + s.sweep_order.sweeps);
    m.sweep_period = static_cast<float>(s.sweep_period_s);
    m.nranges = static_cast<int32_t>(s.scan.ranges_m.size());
    m.ranges = s.scan.ranges_m;
    m.flags = s.scan.flags;
    return m;
}

}  // namespace ugv::lms_daemon
