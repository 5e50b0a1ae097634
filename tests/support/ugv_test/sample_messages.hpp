// One filled-in message of every ugv type, with values that a decoder must reproduce exactly.
// Used by the reflection, Java (lcm-spy) and ugv-dump tests.
#pragma once

#include <cmath>
#include <vector>

#include "ugv/bus/typed.hpp"
#include "ugv/candidate_arcs_t.hpp"
#include "ugv/daemon_status_t.hpp"
#include "ugv/gps_fix_t.hpp"
#include "ugv/gps_velocity_t.hpp"
#include "ugv/imu_t.hpp"
#include "ugv/laser_scan_t.hpp"
#include "ugv/point_cloud_t.hpp"
#include "ugv/pose_t.hpp"
#include "ugv/raw_bytes_t.hpp"
#include "ugv/servo_command_t.hpp"
#include "ugv/servo_state_t.hpp"
#include "ugv/sim_truth_t.hpp"
#include "ugv/terrain_map_t.hpp"
#include "ugv/traversability_map_t.hpp"

namespace ugv::test {

// Publishes one of each type on "SAMPLE_<type>" with utime 1000 + k and seq 10 + k (k = the
// type's index in this order); returns the type names in that order.
inline std::vector<std::string> publish_samples(bus::Bus& b)
{
    int64_t k = 0;
    std::vector<std::string> names;
    auto stamp = [&](auto& m, const char* name) {
        m.utime = 1000 + k;
        m.seq = 10 + k;
        ++k;
        names.push_back(name);
        bus::publish(b, std::string("SAMPLE_") + name, m);
    };
    laser_scan_t scan{};
    scan.sensor_id = "front";
    scan.nranges = 2;
    scan.ranges = {1.25f, NAN};
    scan.flags = {0, laser_scan_t::FLAG_DAZZLE};
    scan.angle_increment = 0.5f;
    scan.nsweeps = 2;
    scan.sweep_order = {1, 0};
    scan.sweep_period = 0.0125f;
    stamp(scan, "laser_scan_t");
    servo_state_t servo{};
    servo.angle = -0.25;
    servo.cia402_state = servo_state_t::STATE_OPERATION_ENABLED;
    stamp(servo, "servo_state_t");
    servo_command_t cmd{};
    cmd.profile = servo_command_t::PROFILE_CONSTANT_RATE;
    cmd.rate = 0.5;
    stamp(cmd, "servo_command_t");
    gps_fix_t fix{};
    fix.latitude = 50.25;
    fix.longitude = -110.5;
    fix.fix_quality = gps_fix_t::QUALITY_DGPS;
    stamp(fix, "gps_fix_t");
    gps_velocity_t vel{};
    vel.horizontal_speed = 3.0;
    stamp(vel, "gps_velocity_t");
    imu_t imu{};
    imu.orientation[0] = 1.0;
    imu.yaw = 1.5;
    stamp(imu, "imu_t");
    pose_t pose{};
    pose.position[0] = 12.5;
    pose.orientation[0] = 1.0;
    stamp(pose, "pose_t");
    point_cloud_t cloud{};
    cloud.sensor_id = "front";
    cloud.npoints = 1;
    cloud.x = {2.0f};
    cloud.y = {0.5f};
    cloud.z = {-0.25f};
    cloud.range = {2.1f};
    cloud.variance = {0.0004f};
    cloud.time_offset = {0.001f};
    stamp(cloud, "point_cloud_t");
    terrain_map_t map{};
    map.resolution = 0.2f;
    map.nx = 1;
    map.ny = 2;
    map.ncells = 2;
    map.mean_z = {0.5f, NAN};
    map.variance_z = {0.01f, NAN};
    map.count = {3, 0};
    map.max_z = {0.75f, NAN};
    map.min_z = {0.25f, NAN};
    map.age_s = {1.5f, NAN};
    stamp(map, "terrain_map_t");
    daemon_status_t status{};
    status.name = "ugv-lms";
    status.ncounters = 1;
    status.counter_names = {"scans"};
    status.counter_values = {375};
    stamp(status, "daemon_status_t");
    raw_bytes_t raw{};
    raw.device = "lms";
    raw.nbytes = 3;
    raw.data = {0x02, 0x80, 0xff};
    stamp(raw, "raw_bytes_t");
    sim_truth_t truth{};
    truth.scenario = "default";
    truth.servo_angle = 0.125;
    stamp(truth, "sim_truth_t");
    traversability_map_t trav{};
    trav.map_seq = 9;
    trav.resolution = 0.2f;
    trav.nx = 1;
    trav.ny = 2;
    trav.ncells = 2;
    trav.cell_class = {traversability_map_t::CLASS_OBSTACLE, traversability_map_t::CLASS_UNKNOWN};
    trav.cost = {1.0f, NAN};
    trav.step_m = {0.5f, NAN};
    trav.drop_m = {0.0f, NAN};
    trav.slope_deg = {12.5f, NAN};
    trav.roughness_m = {0.25f, NAN};
    trav.span_m = {0.75f, NAN};
    trav.certainty = {1.0f, 0.0f};
    stamp(trav, "traversability_map_t");
    candidate_arcs_t arcs{};
    arcs.map_seq = 9;
    arcs.length_m = 12.0f;
    arcs.swept_width_m = 2.25f;
    arcs.narcs = 2;
    arcs.curvature = {-0.125f, 0.125f};
    arcs.clear_distance_m = {4.5f, 12.0f};
    arcs.unknown_fraction = {0.0f, 0.25f};
    arcs.mean_cost = {0.5f, 0.0f};
    arcs.merit = {0.0f, 0.875f};
    arcs.blocked = {1, 0};
    arcs.best = 1;
    stamp(arcs, "candidate_arcs_t");
    return names;
}

}  // namespace ugv::test
