#include "nodscan_messages.hpp"

#include <algorithm>

namespace ugv::nodscan_daemon {

nodscan::ScanView to_scan_view(const laser_scan_t& s)
{
    nodscan::ScanView v;
    v.utime = s.utime;
    v.angle_min = s.angle_min;
    v.angle_increment = s.angle_increment;
    v.time_increment = s.time_increment;
    v.range_max = s.range_max;
    if (s.nsweeps != 0 && !v.set_sweeps(s.sweep_order.data(), std::min<int>(s.nsweeps, static_cast<int>(s.sweep_order.size())),
                      s.sweep_period))
        v.sweeps = 0;  // no valid layout: timing_ok() refuses the scan
    v.ranges = s.ranges.data();
    v.n = std::min<std::size_t>(s.ranges.size(), static_cast<std::size_t>(std::max(0, s.nranges)));
    return v;
}

point_cloud_t to_message(const nodscan::PointCloud& cloud, const std::string& sensor_id, int64_t seq)
{
    point_cloud_t out;
    out.utime = cloud.utime;
    out.seq = seq;
    out.sensor_id = sensor_id;
    for (int i = 0; i < 3; ++i) out.sensor_origin[i] = cloud.sensor_origin(i);
    out.npoints = static_cast<int32_t>(cloud.size());
    out.x = cloud.x;
    out.y = cloud.y;
    out.z = cloud.z;
    out.range = cloud.range;
    out.variance = cloud.variance;
    out.time_offset = cloud.time_offset;
    return out;
}

}  // namespace ugv::nodscan_daemon
