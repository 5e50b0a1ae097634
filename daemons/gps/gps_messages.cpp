#include "gps_messages.hpp"

#include <algorithm>

namespace ugv::gps_daemon {
namespace {

int8_t small_count(int n) { return static_cast<int8_t>(std::clamp(n, -1, 127)); }

}  // namespace

ugv::gps_fix_t to_message(const novatel::Fix& f, int64_t seq)
{
    ugv::gps_fix_t m{};
    m.utime = f.utime;
    m.seq = seq;
    m.gps_week = f.gps_week;
    m.gps_ms = f.gps_ms;
    m.latitude = f.latitude_deg;
    m.longitude = f.longitude_deg;
    m.height = f.height_m;
    m.undulation = static_cast<float>(f.undulation_m);
    m.sigma_latitude = static_cast<float>(f.sigma_latitude_m);
    m.sigma_longitude = static_cast<float>(f.sigma_longitude_m);
    m.sigma_height = static_cast<float>(f.sigma_height_m);
    m.solution_status = f.solution_status;
    m.position_type = f.position_type;
    m.fix_quality = static_cast<int8_t>(f.quality);
    m.satellites_used = small_count(f.satellites_used);
    m.satellites_tracked = small_count(f.satellites_tracked);
    m.differential_age = static_cast<float>(f.differential_age_s);
    m.source = static_cast<int8_t>(f.source);
    return m;
}

ugv::gps_velocity_t to_message(const novatel::VelocityFix& v, int64_t seq)
{
    ugv::gps_velocity_t m{};
    m.utime = v.utime;
    m.seq = seq;
    m.horizontal_speed = v.horizontal_speed_mps;
    m.track = v.track_rad;
    m.vertical_speed = v.vertical_speed_mps;
    m.latency = static_cast<float>(v.latency_s);
    m.solution_status = v.solution_status;
    m.velocity_type = v.velocity_type;
    m.source = static_cast<int8_t>(v.source);
    return m;
}

}  // namespace ugv::gps_daemon
