// Found by test_terrain_bad_messages: ugv-terrain fused a cloud delivered twice twice (its
// points' weight doubled in every cell) without counting it. TerrainNode, no bus.
#include <catch2/catch.hpp>

#include "terrain_node.hpp"

using namespace ugv;

namespace {

pose_t pose_at(int64_t utime)
{
    pose_t p{};
    p.utime = utime;
    p.orientation[0] = 1.0;
    p.status = pose_t::STATUS_OK;
    return p;
}

point_cloud_t cloud_at(int64_t utime, const std::string& sensor, int n)
{
    point_cloud_t c{};
    c.utime = utime;
    c.sensor_id = sensor;
    c.npoints = n;
    for (int k = 0; k < n; ++k) {
        c.x.push_back(4.0f + 0.1f * static_cast<float>(k));
        c.y.push_back(0.0f);
        c.z.push_back(0.0f);
        c.range.push_back(4.0f);
        c.variance.push_back(1e-4f);
        c.time_offset.push_back(0.0f);
    }
    return c;
}

}  // namespace

TEST_CASE("TerrainNode: a cloud delivered twice is fused once and counted; another sensor's cloud of the same time is not a duplicate")
{
    terrain_daemon::TerrainNode node({}, [](const terrain_map_t&) {}, [] { return int64_t{0}; });
    const int64_t t0 = 1'700'000'000'000'000;
    node.on_pose(pose_at(t0));
    const point_cloud_t front = cloud_at(t0 + 50'000, "front", 10);
    node.on_points(front);
    node.on_points(front);
    node.on_points(cloud_at(t0 + 50'000, "rear", 5));
    node.on_pose(pose_at(t0 + 100'000));
    node.flush();
    CHECK(node.counters().clouds_in == 3);
    CHECK(node.counters().clouds_duplicate == 1);
    CHECK(node.mapper().counters().points_fused == 15);
}
