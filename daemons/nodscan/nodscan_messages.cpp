#include "nodscan_messages.hpp"

#include <algorithm>

namespace ugv::nodscan_daemon {

nodscan::ScanView to_scan_view(const laser_scan_t& s) { return nodscan::scan_view_of(s); }

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
