#include "nodscan_node.hpp"

#include <algorithm>

namespace ugv::nodscan_daemon {
namespace {

nodscan::ScanView view_of(const laser_scan_t& s)
{
    nodscan::ScanView v;
    v.utime = s.utime;
    v.angle_min = s.angle_min;
    v.angle_increment = s.angle_increment;
    v.time_increment = s.time_increment;
    v.range_max = s.range_max;
    v.ranges = s.ranges.data();
    v.n = std::min<std::size_t>(s.ranges.size(), static_cast<std::size_t>(std::max(0, s.nranges)));
    return v;
}

}  // namespace

NodscanNode::NodscanNode(const NodscanConfig& config, Publish publish)
    : config_(config), publish_(std::move(publish)), servo_(config.servo_history_us), assembler_(config.assembler)
{
}

void NodscanNode::on_servo(const servo_state_t& msg)
{
    if (!servo_.add({msg.utime, msg.angle})) {
        ++counters_.servo_rejected;
        return;
    }
    newest_message_utime_ = std::max(newest_message_utime_, msg.utime);
    process_ready();
}

void NodscanNode::on_scan(const laser_scan_t& msg)
{
    if (!config_.sensor_id.empty() && msg.sensor_id != config_.sensor_id) {
        ++counters_.scans_other_sensor;
        return;
    }
    ++counters_.scans_in;
    pending_.push_back(msg);
    newest_message_utime_ = std::max(newest_message_utime_, msg.utime);
    while (pending_.size() > config_.max_pending_scans) {
        ++counters_.scans_overflow;
        assemble(pending_.front());  // the oldest has waited longest: use what there is
        pending_.pop_front();
    }
    process_ready();
}

void NodscanNode::process_ready()
{
    while (!pending_.empty()) {
        const laser_scan_t& scan = pending_.front();
        const int64_t last_beam = nodscan::ScanAssembler::last_beam_utime(view_of(scan));
        const bool bracketed = servo_.newest_utime() >= last_beam;
        const bool waited_enough = newest_message_utime_ > last_beam + config_.max_wait_us;
        if (!bracketed && !waited_enough) break;
        assemble(scan);
        pending_.pop_front();
    }
}

void NodscanNode::flush_older_than(int64_t message_utime)
{
    while (!pending_.empty() &&
           nodscan::ScanAssembler::last_beam_utime(view_of(pending_.front())) < message_utime) {
        assemble(pending_.front());
        pending_.pop_front();
    }
}

void NodscanNode::flush_all()
{
    while (!pending_.empty()) {
        assemble(pending_.front());
        pending_.pop_front();
    }
}

void NodscanNode::assemble(const laser_scan_t& scan)
{
    const auto st = assembler_.assemble(view_of(scan), servo_, cloud_);
    counters_.dropped_invalid += st.dropped_invalid;
    counters_.dropped_no_angle += st.dropped_no_angle;
    if (st.points == 0 && st.dropped_no_angle > 0) {
        ++counters_.scans_without_servo;
        return;
    }
    point_cloud_t out;
    out.utime = cloud_.utime;
    out.seq = seq_++;
    out.sensor_id = scan.sensor_id;
    for (int i = 0; i < 3; ++i) out.sensor_origin[i] = cloud_.sensor_origin(i);
    out.npoints = static_cast<int32_t>(cloud_.size());
    out.x = cloud_.x;
    out.y = cloud_.y;
    out.z = cloud_.z;
    out.range = cloud_.range;
    out.variance = cloud_.variance;
    out.time_offset = cloud_.time_offset;
    ++counters_.scans_out;
    counters_.points_out += st.points;
    publish_(out);
}

}  // namespace ugv::nodscan_daemon
