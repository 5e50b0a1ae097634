// Found by test_terrain_bad_messages: ugv-terrain fused a cloud delivered twice twice (its
// points' weight doubled in every cell) without counting it. And clouds whose times would
// overflow the wait arithmetic. TerrainNode, no bus.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

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

TEST_CASE("TerrainNode: an older cloud delivered again after newer ones is still a duplicate")
{
    terrain_daemon::TerrainNode node({}, [](const terrain_map_t&) {}, [] { return int64_t{0}; });
    const int64_t t0 = 1'700'000'000'000'000;
    node.on_pose(pose_at(t0));
    for (int k = 1; k <= 5; ++k) node.on_points(cloud_at(t0 + k * 26'667, "front", 10));
    node.on_points(cloud_at(t0 + 2 * 26'667, "front", 10));  // the second one, again
    node.on_points(cloud_at(t0 + 4 * 26'667, "front", 10));  // and the fourth
    node.on_pose(pose_at(t0 + 200'000));
    node.flush();
    CHECK(node.counters().clouds_in == 7);
    CHECK(node.counters().clouds_duplicate == 2);
    CHECK(node.mapper().counters().points_fused == 50);
}

TEST_CASE("TerrainNode: clouds with no time or absurd point offsets are dropped or bounded, never overflow")
{
    terrain_daemon::TerrainNode node({}, [](const terrain_map_t&) {}, [] { return int64_t{0}; });
    const int64_t t0 = 1'700'000'000'000'000;
    node.on_pose(pose_at(t0));
    node.on_points(cloud_at(0, "front", 10));          // utime 0: no time
    node.on_points(cloud_at(-5'000'000, "front", 10));  // before the epoch
    CHECK(node.counters().clouds_malformed == 2);
    // A point offset of 3e38 s (its end time would overflow int64): the cloud waits by the
    // usual rules, bounded, and is then dropped whole as malformed, since the pose lookups
    // add the offset to its time (UBSan in tools/sanitize checks the arithmetic). A cloud
    // with offsets within 10 s is fused.
    point_cloud_t far = cloud_at(t0 + 50'000, "front", 10);
    far.time_offset[3] = 3e38f;
    node.on_points(far);
    point_cloud_t near = cloud_at(t0 + 60'000, "front", 10);
    near.time_offset[3] = -9.0f;  // before the pose history: that point alone is refused
    node.on_points(near);
    node.on_pose(pose_at(t0 + 100'000));
    node.flush();
    CHECK(node.counters().clouds_in == 4);
    CHECK(node.counters().clouds_malformed == 3);
    CHECK(node.mapper().counters().points_fused == 9);
    CHECK(node.counters().poses_rejected_time == 0);
    node.on_pose(pose_at(0));
    CHECK(node.counters().poses_rejected_time == 1);
}

TEST_CASE("TerrainNode: a cloud stamped far in the future is rejected; it neither blocks the clouds behind it nor stops the maps")
{
    std::vector<int64_t> maps;
    terrain_daemon::TerrainNode node({}, [&](const terrain_map_t& m) { maps.push_back(m.utime); },
                                     [] { return int64_t{0}; });
    const int64_t t0 = 1'700'000'000'000'000;
    // Before any pose: it waits at the head of the queue, then goes when the first pose shows
    // how far ahead it is.
    node.on_points(cloud_at(INT64_MAX, "front", 10));
    node.on_points(cloud_at(t0 + 20'000, "front", 10));
    node.on_pose(pose_at(t0));
    // With poses: rejected on arrival (a year ahead).
    node.on_points(cloud_at(t0 + 365LL * 86'400'000'000, "front", 10));
    for (int k = 1; k <= 30; ++k) {
        node.on_points(cloud_at(t0 + 20'000 + k * 100'000, "front", 10));
        node.on_pose(pose_at(t0 + k * 100'000));
    }
    node.flush();
    CHECK(node.counters().clouds_rejected_time == 2);
    // The other 31 clouds are fused; the last one's points come after the newest pose.
    CHECK(node.mapper().counters().points_fused == 300);
    CHECK(node.mapper().counters().rejected_after_history == 10);
    // Maps at 2 Hz of message time through the 3 s: the future cloud did not move the clock.
    CHECK(maps.size() >= 6);
    CHECK(maps.back() >= t0 + 2'500'000);
}

TEST_CASE("TerrainNode: one pose stamped far in the future is dropped; a real gap is taken once the next pose confirms it")
{
    terrain_daemon::TerrainNode node({}, [](const terrain_map_t&) {}, [] { return int64_t{0}; });
    const int64_t t0 = 1'700'000'000'000'000;
    node.on_pose(pose_at(t0));
    node.on_pose(pose_at(t0 + 365LL * 86'400'000'000));  // a year ahead: a clock gone wrong
    node.on_pose(pose_at(t0 + 100'000));
    node.on_points(cloud_at(t0 + 150'000, "front", 10));
    node.on_pose(pose_at(t0 + 200'000));
    node.flush();
    // Taken, the year-ahead pose would have made every later one out of order.
    CHECK(node.counters().poses_rejected_time == 1);
    CHECK(node.mapper().poses().newest_us() == t0 + 200'000);
    CHECK(node.mapper().counters().points_fused == 10);

    // The pose stream resumes 60 s later: the first pose waits for the second, then both count.
    const int64_t t1 = t0 + 60'000'000;
    node.on_pose(pose_at(t1));
    CHECK(node.mapper().poses().newest_us() == t0 + 200'000);
    node.on_pose(pose_at(t1 + 100'000));
    CHECK(node.mapper().poses().newest_us() == t1 + 100'000);
    node.on_points(cloud_at(t1 + 150'000, "front", 10));
    node.on_pose(pose_at(t1 + 200'000));
    node.flush();
    CHECK(node.counters().poses_rejected_time == 1);
    CHECK(node.mapper().counters().points_fused == 20);

    // Two far-future poses that disagree with each other: neither is taken.
    node.on_pose(pose_at(t1 + 3'600'000'000LL));
    node.on_pose(pose_at(t1 + 7'200'000'000LL));
    node.on_pose(pose_at(t1 + 300'000));
    CHECK(node.counters().poses_rejected_time == 3);
    CHECK(node.mapper().poses().newest_us() == t1 + 300'000);
}

TEST_CASE("TerrainNode: clouds that all carry one time wait in a queue bounded by count")
{
    terrain_daemon::TerrainNode node({}, [](const terrain_map_t&) {}, [] { return int64_t{0}; });
    const int64_t t0 = 1'700'000'000'000'000;
    node.on_pose(pose_at(t0));
    // No pose after them and no newer message: by message time they would wait for ever.
    for (int k = 0; k < 1000; ++k) node.on_points(cloud_at(t0 + 50'000, "s" + std::to_string(k), 4));
    CHECK(node.counters().clouds_overflow == 1000 - 256);
    CHECK(node.mapper().counters().rejected_after_history == 4 * (1000 - 256));
}

TEST_CASE("TerrainNode: clouds with ever new sensor ids keep at most 16 ids for duplicates")
{
    terrain_daemon::TerrainNode node({}, [](const terrain_map_t&) {}, [] { return int64_t{0}; });
    const int64_t t0 = 1'700'000'000'000'000;
    node.on_pose(pose_at(t0));
    node.on_points(cloud_at(t0 + 10'000, "front", 1));
    for (int k = 0; k < 1000; ++k) {
        node.on_points(cloud_at(t0 + 20'000 + k, "s" + std::to_string(k), 1));
        // The vehicle's own laser, heard all along, is never the one forgotten.
        if (k % 10 == 0) node.on_points(cloud_at(t0 + 30'000 + k, "front", 1));
    }
    CHECK(node.counters().sensors_forgotten == 1000 + 1 - 16);
    node.on_points(cloud_at(t0 + 30'000 + 990, "front", 1));
    CHECK(node.counters().clouds_duplicate == 1);
    // A forgotten id's cloud is no longer known as a duplicate: the bound's price.
    node.on_points(cloud_at(t0 + 20'000, "s0", 1));
    CHECK(node.counters().clouds_duplicate == 1);
}
