// Inputs of ugv-terrain for the STATUS and restart tests: a vehicle standing at (east, north)
// facing east, POSE at 10 Hz and a cloud of ground points (z = 0) in front of it at 10 Hz,
// stamped with the wall clock; each cloud covers a new strip, so the map keeps changing.
#pragma once

#include <cmath>
#include <string>

#include <ugv/point_cloud_t.hpp>
#include <ugv/pose_t.hpp>
#include <ugv/terrain_map_t.hpp>

#include "ugv/bus/typed.hpp"
#include "ugv/io/clock.hpp"

namespace ugv::test::status {

struct TerrainFeed
{
    double east_m = 0.0, north_m = 0.0;
    int64_t pose_seq = 0, cloud_seq = 0;

    void pose(bus::Bus& b)
    {
        pose_t p{};
        p.utime = io::now_utime();
        p.seq = pose_seq++;
        p.position[0] = east_m;
        p.position[1] = north_m;
        p.orientation[0] = 1.0;
        for (int k : {0, 4, 8}) {
            p.position_covariance[k] = 0.01;
            p.orientation_covariance[k] = 1e-6;
        }
        p.status = pose_t::STATUS_OK;
        bus::publish(b, "POSE", p);
    }
    // 60 points on a strip across x = 1 .. 8 m, y = -4 .. 4 m; the strip moves with each cloud.
    void cloud(bus::Bus& b)
    {
        point_cloud_t c{};
        c.utime = io::now_utime() - 50'000;  // a pose at or after it is on its way
        c.seq = cloud_seq;
        c.sensor_id = "front";
        const double x = 1.0 + 0.1 * static_cast<double>(cloud_seq % 70);
        ++cloud_seq;
        for (int k = 0; k < 60; ++k) {
            const double y = -4.0 + 8.0 * k / 59.0;
            c.x.push_back(static_cast<float>(x));
            c.y.push_back(static_cast<float>(y));
            c.z.push_back(-0.0f);
            c.range.push_back(static_cast<float>(std::hypot(x, y)));
            c.variance.push_back(0.0004f);
            c.time_offset.push_back(0.0f);
        }
        c.npoints = 60;
        bus::publish(b, "POINTS.front", c);
    }
};

// A small map (10 m x 10 m at 0.2 m: 2,500 cells, 50 kB) so that every map arrives whole.
inline std::string small_map_config() { return "extent_x_m = 10.0\nextent_y_m = 10.0\npublish_hz = 5.0\n"; }

inline int known_cells(const terrain_map_t& m)
{
    int n = 0;
    for (int32_t c : m.count) n += c > 0 ? 1 : 0;
    return n;
}

}  // namespace ugv::test::status
