// Any bytes arriving on a daemon's input channel, decoded as every ugv type the way our code
// does it (reflect::to_json as ugv-dump does; well_formed() then decode() as a typed
// subscription does): never a crash, an exception, an over-read or a huge allocation.
#include <string>

#include "ugv/daemon_status_t.hpp"
#include "ugv/gps_fix_t.hpp"
#include "ugv/gps_velocity_t.hpp"
#include "ugv/imu_t.hpp"
#include "ugv/laser_scan_t.hpp"
#include "ugv/point_cloud_t.hpp"
#include "ugv/pose_t.hpp"
#include "ugv/raw_bytes_t.hpp"
#include "ugv/reflect.hpp"
#include "ugv/servo_command_t.hpp"
#include "ugv/servo_state_t.hpp"
#include "ugv/sim_truth_t.hpp"
#include "ugv/terrain_map_t.hpp"

namespace {
template <typename T>
void decode_as(const uint8_t* data, size_t size)
{
    if (!ugv::reflect::well_formed(data, size)) return;
    T msg;
    (void)msg.decode(data, 0, static_cast<int>(size));
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    std::string type, json;
    (void)ugv::reflect::to_json(data, size, type, json);
    decode_as<ugv::laser_scan_t>(data, size);
    decode_as<ugv::servo_state_t>(data, size);
    decode_as<ugv::servo_command_t>(data, size);
    decode_as<ugv::gps_fix_t>(data, size);
    decode_as<ugv::gps_velocity_t>(data, size);
    decode_as<ugv::imu_t>(data, size);
    decode_as<ugv::pose_t>(data, size);
    decode_as<ugv::point_cloud_t>(data, size);
    decode_as<ugv::terrain_map_t>(data, size);
    decode_as<ugv::daemon_status_t>(data, size);
    decode_as<ugv::raw_bytes_t>(data, size);
    decode_as<ugv::sim_truth_t>(data, size);
    return 0;
}
