// The map kept across a restart (map_state.hpp, TerrainMapper::save_state and
// restore_at_first_pose): the bytes round-trip; a truncated, damaged or foreign buffer is
// refused; a restored map gives the same snapshot; a first pose beyond the extent, or another
// layout, drops it.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <vector>

#include "ugv/terrain/map_state.hpp"
#include "ugv/terrain/terrain_mapper.hpp"

using namespace ugv::terrain;

namespace {

Pose pose_at(int64_t t_us, double x, double y, double yaw_rad)
{
    Pose p;
    p.utime_us = t_us;
    p.position_m = {x, y, 0.0};
    p.orientation = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ());
    return p;
}

MapConfig small_config()
{
    MapConfig c;
    c.extent_x_m = 10.0;
    c.extent_y_m = 10.0;
    c.spread = false;
    return c;
}

// A mapper that drove 3 m east (wrapping rows) with points of heights varying over the map.
TerrainMapper mapped(const MapConfig& c)
{
    TerrainMapper m(c);
    std::vector<float> x, y, z, r, v, t;
    for (int i = 0; i < 40; ++i)
        for (int j = 0; j < 40; ++j) {
            x.push_back(0.2f * static_cast<float>(i) + 0.05f);
            y.push_back(-4.0f + 0.2f * static_cast<float>(j) + 0.05f);
            z.push_back(0.01f * static_cast<float>(i + j));
            r.push_back(std::hypot(x.back(), y.back()));
            v.push_back(0.0004f);
            t.push_back(0.0f);
        }
    for (int k = 0; k <= 30; ++k) {
        REQUIRE(m.add_pose(pose_at(1'000'000 + k * 100'000, 0.1 * k, 2.0, 0.3)) == PoseHistory::AddResult::added);
        PointBatch b;
        b.utime_us = 1'000'000 + k * 100'000;
        b.count = x.size();
        b.x_m = x.data();
        b.y_m = y.data();
        b.z_m = z.data();
        b.range_m = r.data();
        b.variance_m2 = v.data();
        b.time_offset_s = t.data();
        m.fuse(b);
    }
    return m;
}

int known(const MapSnapshot& s)
{
    int n = 0;
    for (int32_t c : s.count) n += c > 0;
    return n;
}

}  // namespace

TEST_CASE("map state: bytes round-trip; truncated, damaged or foreign bytes are refused")
{
    const TerrainMapper m = mapped(small_config());
    MapState s;
    REQUIRE(m.save_state(s));
    REQUIRE(s.cells.size() > 1000);
    const std::vector<uint8_t> bytes = encode_map_state(s);
    CHECK(bytes.size() <= max_encoded_size(s.nx, s.ny));
    std::string why;
    const auto back = decode_map_state(bytes.data(), bytes.size(), why);
    REQUIRE(back);
    CHECK(encode_map_state(*back) == bytes);

    for (std::size_t cut : {std::size_t{0}, std::size_t{7}, std::size_t{95}, bytes.size() / 2, bytes.size() - 1}) {
        INFO("cut at " << cut);
        CHECK_FALSE(decode_map_state(bytes.data(), cut, why));
        CHECK_FALSE(why.empty());
    }
    std::vector<uint8_t> longer = bytes;
    longer.push_back(0);
    CHECK_FALSE(decode_map_state(longer.data(), longer.size(), why));
    for (std::size_t at : {std::size_t{12}, std::size_t{100}, bytes.size() / 2, bytes.size() - 3}) {
        std::vector<uint8_t> damaged = bytes;
        damaged[at] ^= 0x04;
        INFO("flip at " << at);
        CHECK_FALSE(decode_map_state(damaged.data(), damaged.size(), why));
    }
    const std::vector<uint8_t> foreign(4096, 'x');
    CHECK_FALSE(decode_map_state(foreign.data(), foreign.size(), why));
    CHECK(why == "not a ugv-terrain map file");
}

TEST_CASE("map state: restored at a first pose within the extent, the map is the one saved")
{
    const MapConfig c = small_config();
    const TerrainMapper m = mapped(c);
    MapSnapshot before;
    m.snapshot(before);
    MapState s;
    REQUIRE(m.save_state(s));

    TerrainMapper again(c);
    again.restore_at_first_pose(s);
    CHECK(again.restore_outcome() == RestoreOutcome::pending);
    MapState none;
    CHECK_FALSE(again.save_state(none));  // nothing to save before the decision
    const Pose last = m.poses().newest();
    REQUIRE(again.add_pose(pose_at(9'000'000, last.position_m.x(), last.position_m.y(), 0.3)) ==
            PoseHistory::AddResult::added);
    CHECK(again.restore_outcome() == RestoreOutcome::restored);
    CHECK(again.counters().cells_restored == s.cells.size());
    MapSnapshot after;
    again.snapshot(after);
    CHECK(known(after) == known(before));
    CHECK(after.count == before.count);
    CHECK(after.origin_x_m == Approx(before.origin_x_m));
    for (std::size_t k = 0; k < before.mean_z_m.size(); ++k)
        if (before.count[k] > 0) REQUIRE(after.mean_z_m[k] == before.mean_z_m[k]);
}

TEST_CASE("map state: a first pose beyond the extent, or another layout, starts empty")
{
    const MapConfig c = small_config();
    MapState s;
    REQUIRE(mapped(c).save_state(s));
    SECTION("moved 11 m: beyond the 10 m extent")
    {
        TerrainMapper again(c);
        again.restore_at_first_pose(s);
        again.add_pose(pose_at(9'000'000, 3.0 + 11.0, 2.0, 0.3));
        CHECK(again.restore_outcome() == RestoreOutcome::moved);
        CHECK(again.restore_distance_m() == Approx(11.0).margin(0.3));
        MapSnapshot snap;
        again.snapshot(snap);
        CHECK(known(snap) == 0);
    }
    SECTION("another grid size")
    {
        MapConfig other = c;
        other.grid_size_m = 0.25;
        TerrainMapper again(other);
        again.restore_at_first_pose(s);
        again.add_pose(pose_at(9'000'000, 3.0, 2.0, 0.3));
        CHECK(again.restore_outcome() == RestoreOutcome::mismatch);
        MapSnapshot snap;
        again.snapshot(snap);
        CHECK(known(snap) == 0);
    }
}

TEST_CASE("map state: the cells' ages survive a restart, counted on as the clock runs")
{
    const MapConfig c = small_config();
    const TerrainMapper m = mapped(c);  // last pose and batch at 4.0 s, the first at 1.0 s
    MapSnapshot before;
    m.snapshot(before);
    MapState s;
    REQUIRE(m.save_state(s));
    std::string why;
    const std::vector<uint8_t> bytes = encode_map_state(s);
    const auto back = decode_map_state(bytes.data(), bytes.size(), why);
    REQUIRE(back);

    // Restarted 5 s later: every cell is 5 s older than when saved.
    TerrainMapper again(c);
    again.restore_at_first_pose(*back);
    const Pose last = m.poses().newest();
    REQUIRE(again.add_pose(pose_at(last.utime_us + 5'000'000, last.position_m.x(), last.position_m.y(), 0.3)) ==
            PoseHistory::AddResult::added);
    REQUIRE(again.restore_outcome() == RestoreOutcome::restored);
    MapSnapshot after;
    again.snapshot(after);
    int fresh = 0, old = 0;
    for (std::size_t k = 0; k < before.count.size(); ++k) {
        INFO("cell " << k);
        REQUIRE(std::isnan(after.age_s[k]) == std::isnan(before.age_s[k]));
        if (std::isnan(before.age_s[k])) continue;
        CHECK(after.age_s[k] == Approx(before.age_s[k] + 5.0).margin(1e-3));
        fresh += before.age_s[k] < 0.05f ? 1 : 0;
        old += before.age_s[k] > 1.0f ? 1 : 0;
    }
    CHECK(fresh > 100);
    CHECK(old > 10);  // cells last seen before the vehicle drove on
}

TEST_CASE("map state: a file of format 1 (no ages) or a cell without a time is refused")
{
    MapState s;
    REQUIRE(mapped(small_config()).save_state(s));
    std::vector<uint8_t> bytes = encode_map_state(s);
    std::string why;
    std::vector<uint8_t> v1 = bytes;
    const uint32_t one = 1;
    std::memcpy(v1.data() + 8, &one, sizeof one);
    CHECK_FALSE(decode_map_state(v1.data(), v1.size(), why));
    CHECK(why == "format version 1, expected 2");

    s.cells[3].tally.newest_ms = kNoTime;
    bytes = encode_map_state(s);
    CHECK_FALSE(decode_map_state(bytes.data(), bytes.size(), why));
    CHECK(why == "bad cell 3");
}
