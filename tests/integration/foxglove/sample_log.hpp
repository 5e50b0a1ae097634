// A short log of every ugv type on the stack's channels, written with liblcm, and what its
// MCAP must hold: the topics and their message counts, and the terrain maps' cells.
#pragma once

#include <lcm/lcm-cpp.hpp>

#include <cmath>
#include <map>
#include <string>

#include "ugv/candidate_arcs_t.hpp"
#include "ugv/daemon_status_t.hpp"
#include "ugv/gps_fix_t.hpp"
#include "ugv/imu_t.hpp"
#include "ugv/laser_scan_t.hpp"
#include "ugv/point_cloud_t.hpp"
#include "ugv/pose_t.hpp"
#include "ugv/servo_state_t.hpp"
#include "ugv/terrain_map_t.hpp"
#include "ugv/traversability_map_t.hpp"
#include "ugv_test/encoded.hpp"

namespace ugv::test {

constexpr int kMapNx = 40, kMapNy = 30;

inline float map_height(int map, int i, int j) { return 0.01f * static_cast<float>(i) - 0.02f * static_cast<float>(j) + static_cast<float>(map); }

// Writes the log; returns the expected message count of each topic (the events per channel,
// and per well-known topic).
inline std::map<std::string, int> write_sample_log(const std::string& path)
{
    lcm::LogFile log(path, "w");
    std::map<std::string, int> counts;
    int64_t t = 1'700'000'000'000'000;
    auto put = [&](const std::string& channel, const auto& msg, std::initializer_list<const char*> topics) {
        write_event(log, t, channel, msg);
        t += 10'000;
        ++counts[channel];
        for (const char* suffix : topics) ++counts[channel + "/" + suffix];
    };
    pose_t pose{};
    pose.orientation[0] = 1;
    for (int k = 0; k < 60; ++k) {
        pose.utime = t;
        pose.seq = k;
        pose.position[0] = 0.1 * k;
        if (k % 2 == 0) put("POSE", pose, {"tf", "pose"});
        servo_state_t servo{};
        servo.utime = t;
        servo.angle = 0.01 * k;
        put("SERVO_STATE", servo, {"tf"});
        if (k % 3 == 0) {
            laser_scan_t scan{};
            scan.utime = t;
            scan.sensor_id = "front";
            scan.angle_min = -1.5708f;
            scan.angle_increment = 0.00872665f;
            scan.nranges = 361;
            for (int b = 0; b < 361; ++b) {
                scan.ranges.push_back(b % 50 == 0 ? NAN : 5.0f + 0.01f * static_cast<float>(b));
                scan.flags.push_back(b % 50 == 0 ? laser_scan_t::FLAG_OVERFLOW : laser_scan_t::FLAG_OK);
            }
            put("LMS_SCAN", scan, {"scan"});
            point_cloud_t cloud{};
            cloud.utime = t;
            cloud.sensor_id = "front";
            cloud.sensor_origin[2] = 1.2;
            cloud.npoints = 100;
            for (int p = 0; p < 100; ++p) {
                for (auto* v : {&cloud.x, &cloud.y, &cloud.z, &cloud.range, &cloud.variance, &cloud.time_offset})
                    v->push_back(0.01f * static_cast<float>(p));
            }
            put("POINTS", cloud, {"cloud"});
        }
        if (k % 10 == 0) {
            gps_fix_t fix{};
            fix.utime = t;
            fix.latitude = 50.25 + 1e-6 * k;
            fix.longitude = -110.5;
            fix.sigma_latitude = fix.sigma_longitude = 0.5f;
            fix.sigma_height = 1.0f;
            put("GPS_FIX", fix, {"fix"});
            imu_t imu{};
            imu.utime = t;
            imu.orientation[0] = 1;
            put("IMU", imu, {});
        }
        if (k % 20 == 0) {
            const int map = k / 20;
            terrain_map_t m{};
            m.utime = t;
            m.pose = pose;
            m.resolution = 0.2f;
            m.nx = kMapNx;
            m.ny = kMapNy;
            m.ncells = kMapNx * kMapNy;
            m.origin_x = -0.5f;
            m.origin_y = -3.0f;
            for (int i = 0; i < kMapNx; ++i)
                for (int j = 0; j < kMapNy; ++j) {
                    const float z = map_height(map, i, j);
                    m.mean_z.push_back((i + j) % 7 == 0 ? NAN : z);
                    m.variance_z.push_back(0.001f);
                    m.count.push_back(i + j);
                    m.max_z.push_back(z + 0.05f);
                    m.min_z.push_back(z - 0.05f);
                    m.age_s.push_back(0.5f);
                }
            put("TERRAIN_MAP", m, {"grid"});
            traversability_map_t tm{};
            tm.utime = t;
            tm.map_seq = map;
            tm.pose = pose;
            tm.resolution = 0.2f;
            tm.nx = kMapNx;
            tm.ny = kMapNy;
            tm.ncells = kMapNx * kMapNy;
            tm.cell_class.assign(static_cast<std::size_t>(tm.ncells), traversability_map_t::CLASS_TRAVERSABLE);
            for (auto* v : {&tm.cost, &tm.step_m, &tm.drop_m, &tm.slope_deg, &tm.roughness_m, &tm.span_m, &tm.certainty})
                v->assign(static_cast<std::size_t>(tm.ncells), 0.25f);
            put("TRAVERSABILITY_MAP", tm, {"grid"});
            candidate_arcs_t arcs{};
            arcs.utime = t;
            arcs.pose = pose;
            arcs.length_m = 8;
            arcs.narcs = 3;
            arcs.curvature = {-0.1f, 0, 0.1f};
            arcs.clear_distance_m = {8, 3, 8};
            arcs.unknown_fraction = {0, 0, 0};
            arcs.mean_cost = {0.1f, 0.2f, 0.1f};
            arcs.merit = {0.9f, 0, 0.8f};
            arcs.blocked = {0, 1, 0};
            arcs.best = 0;
            put("ARCS", arcs, {"scene"});
        }
    }
    // Status: RUNNING, RUNNING, DEGRADED (error), the same, RUNNING: three changes, three logs.
    const int8_t states[] = {1, 1, 2, 2, 1};
    for (int k = 0; k < 5; ++k) {
        daemon_status_t s{};
        s.utime = t;
        s.name = "ugv-lms";
        s.state = states[k];
        s.last_error = states[k] == 2 ? "no scan for 0.5 s" : "";
        write_event(log, t, "STATUS_LMS", s);
        t += 10'000;
        ++counts["STATUS_LMS"];
    }
    counts["STATUS_LMS/log"] = 3;
    // A message of no ugv type: not a topic.
    lcm::LogEvent ev{};
    ev.timestamp = t;
    ev.channel = "FOREIGN";
    const char foreign[] = "not an ugv message";
    ev.datalen = sizeof foreign;
    ev.data = const_cast<char*>(foreign);
    log.writeEvent(&ev);
    return counts;
}

}  // namespace ugv::test
