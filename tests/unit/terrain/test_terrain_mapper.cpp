#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include "ugv/terrain/simd.hpp"
#include "ugv/terrain/terrain_mapper.hpp"

using namespace ugv::terrain;

namespace {

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();

Pose pose_at(int64_t t_us, double x, double y, double yaw_rad, double orientation_var_rad2 = 0.0)
{
    Pose p;
    p.utime_us = t_us;
    p.position_m = {x, y, 0.0};
    p.orientation = Eigen::AngleAxisd(yaw_rad, Eigen::Vector3d::UnitZ());
    p.orientation_covariance_rad2 = Eigen::Matrix3d::Identity() * orientation_var_rad2;
    return p;
}

// Points in the body frame, all at one time, with a given sensor variance and range.
struct Points
{
    std::vector<float> x, y, z, range, variance, t;
    void add(float px, float py, float pz, float var_m2 = 0.01f, float t_s = 0.0f, float r_m = -1.0f)
    {
        x.push_back(px);
        y.push_back(py);
        z.push_back(pz);
        range.push_back(std::isnan(r_m) || r_m >= 0.0f ? r_m : std::sqrt(px * px + py * py));
        variance.push_back(var_m2);
        t.push_back(t_s);
    }
    PointBatch batch(int64_t utime_us) const
    {
        PointBatch b;
        b.utime_us = utime_us;
        b.count = x.size();
        b.x_m = x.data();
        b.y_m = y.data();
        b.z_m = z.data();
        b.range_m = range.data();
        b.variance_m2 = variance.data();
        b.time_offset_s = t.data();
        return b;
    }
};

MapConfig base_config()
{
    MapConfig c;
    c.spread = false;
    return c;
}

int known_cells(const MapSnapshot& s)
{
    int n = 0;
    for (float z : s.mean_z_m) n += std::isnan(z) ? 0 : 1;
    return n;
}

}  // namespace

TEST_CASE("driving 1.0 m forward at G_l = 0.2 wraps 5 rows and clears them")
{
    TerrainMapper m(base_config());  // reference point: rear bumper, 0.5 m behind the body origin
    REQUIRE(m.add_pose(pose_at(0, 0.0, 0.0, 0.0)) == PoseHistory::AddResult::added);
    // One point in each of the unwrapped rows 0..6 (row k's centre is 0.1 + 0.2 k m ahead of
    // the rear bumper), column 75, height k.
    Points p;
    for (int k = 0; k < 7; ++k) p.add(-0.5f + 0.1f + 0.2f * static_cast<float>(k), 0.1f, static_cast<float>(k));
    REQUIRE(m.fuse(p.batch(0)) == 7);
    MapSnapshot s;
    m.snapshot(s);
    REQUIRE(known_cells(s) == 7);
    CHECK(s.mean_z_m[0 * 150 + 75] == 0.0f);
    CHECK(s.mean_z_m[6 * 150 + 75] == 6.0f);

    REQUIRE(m.add_pose(pose_at(1'000'000, 1.0, 0.0, 0.0)) == PoseHistory::AddResult::added);
    CHECK(m.counters().wraps == 5);
    m.snapshot(s);
    CHECK(s.wrap_index == 5);
    CHECK(s.x_curr_m == Approx(0.0).margin(1e-9));
    // The rows driven over are gone; old row 5 is now row 0, old row 6 row 1.
    CHECK(known_cells(s) == 2);
    CHECK(s.mean_z_m[0 * 150 + 75] == 5.0f);
    CHECK(s.mean_z_m[1 * 150 + 75] == 6.0f);
    // The five recycled rows are now the far rows, and empty.
    for (int i = 145; i < 150; ++i) CHECK(s.count[static_cast<std::size_t>(i * 150 + 75)] == 0);
    // A point at the far end now lands in a recycled row.
    Points far;
    far.add(-0.5f + 1.0f + 29.9f - 1.0f, 0.1f, 9.0f);  // body x 29.4 -> 29.9 from the rear bumper
    REQUIRE(m.fuse(far.batch(1'000'000)) == 1);
    m.snapshot(s);
    CHECK(s.mean_z_m[149 * 150 + 75] == 9.0f);
}

TEST_CASE("forward motion is projected on the heading; the remainder is kept")
{
    TerrainMapper m(base_config());
    m.add_pose(pose_at(0, 0.0, 0.0, 0.0));
    m.add_pose(pose_at(100'000, 0.35, 0.0, 0.0));  // 1 row and 0.15 m
    CHECK(m.counters().wraps == 1);
    m.add_pose(pose_at(200'000, 0.45, 0.0, 0.0));  // 0.25 m of 0.4: still 1 row, remainder 0.05
    CHECK(m.counters().wraps == 2);
    MapSnapshot s;
    m.snapshot(s);
    CHECK(s.x_curr_m == Approx(0.05));
    // Sideways motion does not advance the map (it re-centres by whole columns).
    m.add_pose(pose_at(300'000, 0.45, 0.5, 0.0));
    CHECK(m.counters().wraps == 2);
    CHECK(m.counters().recentres == 1);
    // Reversing goes back.
    m.add_pose(pose_at(400'000, 0.0, 0.5, 0.0));
    CHECK(m.counters().wraps == 4);  // x_curr 0.05 - 0.45 = -0.40: two rows back
    m.snapshot(s);
    CHECK(s.x_curr_m == Approx(0.0).margin(1e-9));
}

static void turn_ninety_degrees(MapMode mode)
{
    MapConfig c = base_config();
    c.mode = mode;
    c.reference_x_m = 0.0;  // spin about the reference point
    c.theta_d_rad = 5.0 * M_PI / 180.0;
    TerrainMapper m(c);
    m.add_pose(pose_at(0, 0.0, 0.0, 0.0));
    // An obstacle 5.1 m ahead and 2.1 m to the left (a cell centre), 1 m high.
    Points p;
    p.add(5.1f, 2.1f, 1.0f);
    REQUIRE(m.fuse(p.batch(0)) == 1);
    // Turn left 90 deg in place, 1 deg per pose: 18 rotations of theta_d.
    for (int k = 1; k <= 90; ++k)
        REQUIRE(m.add_pose(pose_at(k * 50'000, 0.0, 0.0, k * M_PI / 180.0)) == PoseHistory::AddResult::added);
    if (mode == MapMode::egocentric) CHECK(m.counters().rotations >= 17);
    // The obstacle is now 2.1 m ahead and 5.1 m to the right.
    const CellStatistics at = m.statistics_at_body(2.1, -5.1);
    CHECK(at.mean_z_m == Approx(1.0));
    MapSnapshot s;
    m.snapshot(s);
    REQUIRE(known_cells(s) == 1);
    // Find it in the published layout: cell (i, j) centre, in the map axes, from the body origin.
    std::size_t k = 0;
    while (std::isnan(s.mean_z_m[k])) ++k;
    const double mx = s.origin_x_m + (static_cast<double>(k / 150) + 0.5) * s.resolution_m;
    const double my = s.origin_y_m + (static_cast<double>(k % 150) + 0.5) * s.resolution_m;
    // Map axes are the body axes turned by -residual_yaw: body = R(-residual_yaw) map.
    const double cr = std::cos(s.residual_yaw_rad), sr = std::sin(s.residual_yaw_rad);
    const double bx = cr * mx + sr * my, by = -sr * mx + cr * my;
    CHECK(std::abs(bx - 2.1) < 0.15);
    CHECK(std::abs(by + 5.1) < 0.15);
    CHECK(s.mean_z_m[k] == 1.0f);
}

TEST_CASE("a single-cell obstacle lands in the right cell after a 90 deg turn, egocentric")
{
    turn_ninety_degrees(MapMode::egocentric);
}

TEST_CASE("a single-cell obstacle lands in the right cell after a 90 deg turn, world-aligned")
{
    turn_ninety_degrees(MapMode::world_aligned);
}

TEST_CASE("the rear-bumper reference keeps an obstacle beside the vehicle")
{
    MapConfig rear = base_config();
    MapConfig front = base_config();
    front.reference_x_m = 2.0;  // the report's front bumper
    TerrainMapper a(rear), b(front);
    Points p;
    p.add(0.7f, 1.5f, 0.8f);  // beside the vehicle, between its bumpers
    for (TerrainMapper* m : {&a, &b}) {
        m->add_pose(pose_at(0, 0.0, 0.0, 0.0));
        m->fuse(p.batch(0));
    }
    CHECK(a.statistics_at_body(0.7, 1.5).mean_z_m == Approx(0.8));
    CHECK(std::isnan(b.statistics_at_body(0.7, 1.5).mean_z_m));
    CHECK(b.counters().rejected_outside_map == 1);
}

TEST_CASE("NaN points and NaN poses never reach a cell")
{
    TerrainMapper m(base_config());
    Pose bad = pose_at(0, 0.0, 0.0, 0.0);
    bad.position_m.y() = std::numeric_limits<double>::quiet_NaN();
    CHECK(m.add_pose(bad) == PoseHistory::AddResult::non_finite);
    Pose bad_q = pose_at(0, 0.0, 0.0, 0.0);
    bad_q.orientation.w() = std::numeric_limits<double>::infinity();
    CHECK(m.add_pose(bad_q) == PoseHistory::AddResult::non_finite);
    CHECK(m.counters().poses_rejected_non_finite == 2);
    CHECK_FALSE(m.has_pose());
    Points p;
    p.add(3.0f, 0.0f, 1.0f);
    CHECK(m.fuse(p.batch(0)) == 0);
    CHECK(m.counters().rejected_no_pose == 1);

    m.add_pose(pose_at(0, 0.0, 0.0, 0.0));
    Points q;
    q.add(kNan, 0.0f, 1.0f);
    q.add(3.0f, kNan, 1.0f);
    q.add(3.0f, 0.0f, kNan);
    q.add(3.0f, 0.0f, 1.0f, kNan);
    q.add(3.0f, 0.0f, 1.0f, 0.01f, kNan);
    q.add(3.0f, 0.0f, 1.0f, 0.01f, 0.0f, kNan);
    q.add(std::numeric_limits<float>::infinity(), 0.0f, 1.0f);
    q.add(3.0f, 0.0f, 1.0f, -0.01f);  // a negative variance is not a variance
    CHECK(m.fuse(q.batch(0)) == 0);
    CHECK(m.counters().rejected_non_finite == 8);
    CHECK(m.total().n == 0);
    CHECK(m.total().w == 0.0);
    MapSnapshot s;
    m.snapshot(s);
    CHECK(known_cells(s) == 0);
}

TEST_CASE("each point is transformed with the pose at its own time")
{
    MapConfig c = base_config();
    c.reference_x_m = 0.0;
    TerrainMapper m(c);
    m.add_pose(pose_at(0, 0.0, 0.0, 0.0));
    m.add_pose(pose_at(1'000'000, 1.0, 0.0, 0.0));
    // Slow path (the batch spans 0.5 s): points at 0.25 s and 0.75 s.
    Points slow;
    slow.add(2.05f, 0.1f, 1.0f, 0.01f, 0.25f);  // world x 2.30 -> body x now 1.30
    slow.add(2.05f, 0.1f, 2.0f, 0.01f, 0.75f);  // world x 2.80 -> body x now 1.80
    REQUIRE(m.fuse(slow.batch(0)) == 2);
    CHECK(m.statistics_at_body(1.30, 0.1).mean_z_m == Approx(1.0));
    CHECK(m.statistics_at_body(1.80, 0.1).mean_z_m == Approx(2.0));
    // Fast path (span 20 ms): blended between the poses at both ends.
    Points fast;
    fast.add(4.05f, 0.3f, 3.0f, 0.01f, 0.0f);   // at 0.50 s: world 4.55 -> body 3.55
    fast.add(4.05f, 0.5f, 4.0f, 0.01f, 0.02f);  // at 0.52 s: world 4.57 -> body 3.57
    REQUIRE(m.fuse(fast.batch(500'000)) == 2);
    CHECK(m.statistics_at_body(3.55, 0.3).mean_z_m == Approx(3.0));
    CHECK(m.statistics_at_body(3.57, 0.5).mean_z_m == Approx(4.0));
    CHECK(m.total().n == 4);
    // Out of the history: before the oldest and after the newest pose, counted by reason.
    Points out;
    out.add(2.0f, 0.0f, 1.0f, 0.01f, -0.5f);
    out.add(2.0f, 0.0f, 1.0f, 0.01f, 1.5f);
    out.add(2.0f, 0.0f, 1.0f, 0.01f, 0.1f);
    CHECK(m.fuse(out.batch(0)) == 1);
    CHECK(m.counters().rejected_before_history == 1);
    CHECK(m.counters().rejected_after_history == 1);
}

TEST_CASE("eq. 19: the orientation error comes from the pose covariance at the point's time")
{
    MapConfig c = base_config();
    TerrainMapper m(c);
    Pose a = pose_at(0, 0.0, 0.0, 0.0);
    a.orientation_covariance_rad2.diagonal() << 1e-4, 4e-4, 1e-4;
    Pose b = pose_at(100'000, 0.0, 0.0, 0.0);
    b.orientation_covariance_rad2.diagonal() << 1e-4, 8e-4, 1e-4;
    m.add_pose(a);
    m.add_pose(b);
    Points p;
    p.add(3.0f, 0.1f, 0.5f, 0.001f, 0.05f, 5.0f);  // r = 5 m at 50 ms: de^2 = 6e-4 rad^2
    REQUIRE(m.fuse(p.batch(0)) == 1);
    // s2 = 0.001 + 2 * 25 * 6e-4 = 0.031 m^2; weight 1/0.031.
    CHECK(m.total().w == Approx(1.0 / 0.031).epsilon(1e-5));
}

TEST_CASE("section 3.5: spreading conserves total weight")
{
    MapConfig c;
    c.spread = true;
    c.spread_max_cells = 2;
    TerrainMapper m(c);
    m.add_pose(pose_at(0, 0.0, 0.0, 0.0));
    Points p;
    p.add(10.03f, 0.07f, 2.0f, 0.09f);   // sigma 0.3 m > G_l: spread
    p.add(12.0f, -3.0f, 1.0f, 0.01f);    // sigma 0.1 m: one cell
    p.add(20.05f, 1.05f, 3.0f, 4.0f);    // sigma 2 m: capped at 2 cells each way
    REQUIRE(m.fuse(p.batch(0)) == 3);
    CHECK(m.counters().points_spread == 2);
    const MapTotals total = m.total();
    CHECK(total.w == Approx(1.0 / 0.09 + 1.0 / 0.01 + 1.0 / 4.0).epsilon(1e-5));
    CHECK(total.w_z == Approx(2.0 / 0.09 + 1.0 / 0.01 + 3.0 / 4.0).epsilon(1e-5));
    MapSnapshot s;
    m.snapshot(s);
    // 10.53 +/- 0.3 m from the rear bumper spans rows 51-54, 0.07 +/- 0.3 columns 73-76: 4 x 4;
    // then one cell; then +/- 0.4 m (2 cells) around an off-edge point: 5 x 5.
    CHECK(known_cells(s) == 16 + 1 + 25);
    for (std::size_t k = 0; k < s.mean_z_m.size(); ++k)
        if (!std::isnan(s.mean_z_m[k])) CHECK((s.mean_z_m[k] == Approx(2.0f) || s.mean_z_m[k] == Approx(1.0f) || s.mean_z_m[k] == Approx(3.0f)));
}

TEST_CASE("section 3.5: a spread point's height reaches only its own cell's max (no ghost beside a box)")
{
    // The mechanism of the ghosts beside boxes in turns: a box-top point with sigma > G is
    // spread over the ground cells beside the box; its height must not become their max.
    for (const MapMode mode : {MapMode::egocentric, MapMode::world_aligned}) {
        INFO((mode == MapMode::egocentric ? "egocentric" : "world aligned"));
        MapConfig c;
        c.mode = mode;
        c.spread = true;
        c.spread_max_cells = 2;
        TerrainMapper m(c);
        m.add_pose(pose_at(0, 0.0, 0.0, 0.0));
        // Cell (i, j) of the egocentric layout: x = -0.5 + (i + 0.5) G ahead of the body
        // origin, y = -15 + (j + 0.5) G; the world grid is resampled into the same layout.
        auto cx = [](int i) { return static_cast<float>(-0.5 + (i + 0.5) * 0.2); };
        auto cy = [](int j) { return static_cast<float>(-15.0 + (j + 0.5) * 0.2); };
        Points ground;  // sigma 1 cm: each in its own cell; a 0.5 m box on columns 75-78 of rows 52-54
        for (int i = 50; i <= 56; ++i)
            for (int j = 71; j <= 78; ++j) {
                const bool box = i >= 52 && i <= 54 && j >= 75;
                for (int k = 0; k < 4; ++k) ground.add(cx(i), cy(j), box ? 0.5f : 0.0f, 1e-4f);
            }
        REQUIRE(m.fuse(ground.batch(0)) == 7 * 8 * 4);
        Points top;  // the box's top 2 cm inside its edge, sigma 0.3 m (far range, a turn's yaw sigma)
        top.add(cx(53), 0.02f, 0.5f, 0.09f);
        top.add(cx(60), cy(60), 0.7f, 0.09f);  // alone on unknown ground: a spread-only cell has extremes too
        REQUIRE(m.fuse(top.batch(0)) == 2);
        REQUIRE(m.counters().points_spread == 2);
        MapSnapshot s;
        m.snapshot(s);
        auto k = [](int i, int j) { return static_cast<std::size_t>(i * 150 + j); };
        CHECK(s.max_z_m[k(53, 75)] == Approx(0.5f));  // the point's own cell
        for (int i = 52; i <= 54; ++i)
            for (int j = 73; j <= 74; ++j) {
                INFO("ground cell " << i << ", " << j << " beside the box");
                CHECK(s.max_z_m[k(i, j)] < 0.01f);
                CHECK(s.count[k(i, j)] == 5);  // N still counts the spread point in every cell it touches
            }
        for (std::size_t q = 0; q < s.mean_z_m.size(); ++q) {
            INFO("cell " << q);
            REQUIRE(std::isnan(s.max_z_m[q]) == std::isnan(s.mean_z_m[q]));
            REQUIRE(std::isnan(s.min_z_m[q]) == std::isnan(s.mean_z_m[q]));
            if (std::isnan(s.mean_z_m[q])) continue;
            CHECK(s.min_z_m[q] <= s.mean_z_m[q] + 1e-5f);
            CHECK(s.mean_z_m[q] <= s.max_z_m[q] + 1e-5f);
        }
        CHECK(s.max_z_m[k(60, 60)] == Approx(0.7f));
        CHECK(s.max_z_m[k(60, 61)] == Approx(0.7f));  // nothing else there: the mean is the point's
    }
}

TEST_CASE("spreading conserves total weight at the map's edge and in the world-aligned mode")
{
    MapConfig c;
    c.spread = true;
    c.mode = MapMode::world_aligned;
    TerrainMapper m(c);
    m.add_pose(pose_at(0, 100.0, -40.0, 0.7));
    Points p;
    p.add(5.0f, 0.0f, 1.0f, 0.16f);
    REQUIRE(m.fuse(p.batch(0)) == 1);
    CHECK(m.total().w == Approx(1.0 / 0.16).epsilon(1e-5));
}

TEST_CASE("classical and variance-weighted statistics differ as eq. 21 vs 23 say")
{
    MapConfig c = base_config();
    c.reference_x_m = 0.0;
    MapConfig k = c;
    k.statistics = StatisticsKind::classical;
    TerrainMapper vw(c), cl(k);
    Points p;
    p.add(3.1f, 0.1f, 1.0f, 1.0f);
    p.add(3.1f, 0.1f, 3.0f, 3.0f);
    for (TerrainMapper* m : {&vw, &cl}) {
        m->add_pose(pose_at(0, 0.0, 0.0, 0.0));
        m->fuse(p.batch(0));
    }
    CHECK(vw.statistics_at_body(3.1, 0.1).mean_z_m == Approx(1.5));
    CHECK(vw.statistics_at_body(3.1, 0.1).variance_z_m2 == Approx(0.75));
    CHECK(cl.statistics_at_body(3.1, 0.1).mean_z_m == Approx(2.0));
    CHECK(cl.statistics_at_body(3.1, 0.1).variance_z_m2 == Approx(2.0));
}

TEST_CASE("a pose jump larger than the map resets it; bad configurations are refused")
{
    TerrainMapper m(base_config());
    m.add_pose(pose_at(0, 0.0, 0.0, 0.0));
    Points p;
    p.add(3.0f, 0.0f, 1.0f);
    m.fuse(p.batch(0));
    m.add_pose(pose_at(100'000, 500.0, 0.0, 0.0));
    CHECK(m.counters().resets == 1);
    CHECK(m.total().n == 0);
    MapConfig bad;
    bad.grid_size_m = 0.0;
    CHECK_THROWS_AS(TerrainMapper(bad), std::invalid_argument);
    bad = MapConfig{};
    bad.theta_d_rad = -1.0;
    CHECK_THROWS_AS(TerrainMapper(bad), std::invalid_argument);
}

namespace {

// Two poses 20 ms apart, and 361 points (not a multiple of 8) over that time: ground
// ahead, some far outside, some with a NaN, a negative variance or a large variance (to
// be spread), fused into a map of the given mode.
// max_span_s: above 0.02, the scan takes the vector placement (the end transforms blended);
// below, runs of it do, or with split false the scalar path (each point's pose interpolated
// on its own).
MapSnapshot fuse_mixed_scan(MapMode mode, MapCounters& counters, double max_span_s = 0.1, bool split = true)
{
    MapConfig c;
    c.mode = mode;
    c.max_interpolation_span_s = max_span_s;
    c.split_long_batches = split;
    TerrainMapper m(c);
    // A sideways step of 2.5 columns first: the egocentric map's column ring then has m_j = 2
    // (recentred by shift_columns), which the placement kernels must follow as locate() does.
    REQUIRE(m.add_pose(pose_at(0, 0.0, -0.5, 0.0, 1e-4)) == PoseHistory::AddResult::added);
    REQUIRE(m.add_pose(pose_at(10'000, 0.0, 0.0, 0.0, 1e-4)) == PoseHistory::AddResult::added);
    REQUIRE(m.add_pose(pose_at(30'000, 0.02, 0.001, 0.004, 2e-4)) == PoseHistory::AddResult::added);
    if (mode == MapMode::egocentric) REQUIRE(m.counters().recentres == 1);
    Points p;
    for (int k = 0; k < 361; ++k) {
        const float a = static_cast<float>(k) * 0.0087f - 1.57f;
        const float r = 2.0f + 0.03f * static_cast<float>(k % 97);
        float var = 1e-4f * static_cast<float>(1 + k % 5);
        float x = r * std::cos(a), y = r * std::sin(a), z = -0.8f + 0.01f * static_cast<float>(k % 7);
        if (k % 53 == 0) x = kNan;
        if (k % 61 == 0) var = -1.0f;
        if (k % 67 == 0) var = 0.3f;  // sigma 0.55 m > G: spread
        if (k % 71 == 0) y = 40.0f;   // beyond the map's side
        p.add(x, y, z, var, 0.02f * static_cast<float>(k) / 361.0f, r);
    }
    m.fuse(p.batch(10'000));
    counters = m.counters();
    MapSnapshot s;
    m.snapshot(s);
    return s;
}

}  // namespace

TEST_CASE("the fusion's AVX2 and generic builds give the same map and the same counters")
{
    if (best_simd_level() != SimdLevel::avx2) {
        WARN("skipped: this CPU runs only the generic code");
        return;
    }
    for (const MapMode mode : {MapMode::egocentric, MapMode::world_aligned}) {
        MapCounters wide_counters, generic_counters;
        const MapSnapshot wide = fuse_mixed_scan(mode, wide_counters);
        const MapSnapshot generic = [&] {
            const ScopedSimdLevel use(SimdLevel::generic);
            return fuse_mixed_scan(mode, generic_counters);
        }();
        CHECK(wide_counters.points_fused == generic_counters.points_fused);
        CHECK(wide_counters.points_spread == generic_counters.points_spread);
        CHECK(wide_counters.rejected_non_finite == generic_counters.rejected_non_finite);
        CHECK(wide_counters.rejected_outside_map == generic_counters.rejected_outside_map);
        CHECK(generic_counters.rejected_non_finite == 12);  // 7 NaN x, 6 negative variances, point 0 both
        CHECK(generic_counters.points_spread > 0);
        REQUIRE(wide.mean_z_m.size() == generic.mean_z_m.size());
        int known = 0;
        for (std::size_t k = 0; k < wide.mean_z_m.size(); ++k) {
            INFO("cell " << k);
            CHECK(std::isnan(wide.mean_z_m[k]) == std::isnan(generic.mean_z_m[k]));
            CHECK(wide.count[k] == generic.count[k]);
            if (std::isnan(generic.mean_z_m[k])) continue;
            ++known;
            CHECK(wide.mean_z_m[k] == Approx(generic.mean_z_m[k]).margin(1e-5));
            CHECK(wide.variance_z_m2[k] == Approx(generic.variance_z_m2[k]).margin(1e-6));
        }
        CHECK(known > 100);
    }
}

// The scalar path (fuse_point, CellArray::fuse) is the fusion's reference: each placement
// kernel must put every point where it puts it, up to the blend of the end transforms
// (< 1e-5 m here) and float rounding, which may move a point that lies on a cell edge.
TEST_CASE("each placement kernel fuses a scan as the scalar path does")
{
    for (const SimdLevel level : {SimdLevel::generic, SimdLevel::avx2}) {
        if (static_cast<int>(level) > static_cast<int>(best_simd_level())) {
            WARN("skipped: this CPU cannot run the " << to_string(level) << " code");
            continue;
        }
        const ScopedSimdLevel use(level);
        for (const MapMode mode : {MapMode::egocentric, MapMode::world_aligned}) {
            INFO("simd level " << to_string(level) << ", mode " << static_cast<int>(mode));
            MapCounters kernel_counters, run_counters, scalar_counters;
            const MapSnapshot kernel = fuse_mixed_scan(mode, kernel_counters);
            // 20 ms in runs of at most 5 ms, each blended between its own end poses.
            const MapSnapshot runs = fuse_mixed_scan(mode, run_counters, 0.005);
            const MapSnapshot scalar = fuse_mixed_scan(mode, scalar_counters, 0.001, false);
            auto agree = [&](const MapSnapshot& fused, const MapCounters& counters) {
                CHECK(counters.points_fused == scalar_counters.points_fused);
                CHECK(counters.points_spread == scalar_counters.points_spread);
                CHECK(counters.rejected_non_finite == scalar_counters.rejected_non_finite);
                CHECK(counters.rejected_outside_map == scalar_counters.rejected_outside_map);
                int same = 0, differ = 0;
                for (std::size_t k = 0; k < scalar.count.size(); ++k) {
                    if (fused.count[k] != scalar.count[k]) {
                        ++differ;
                        continue;
                    }
                    if (scalar.count[k] == 0) continue;
                    INFO("cell " << k);
                    ++same;
                    CHECK(fused.mean_z_m[k] == Approx(scalar.mean_z_m[k]).margin(1e-4));
                    CHECK(fused.max_z_m[k] == Approx(scalar.max_z_m[k]).margin(1e-4));
                    CHECK(fused.min_z_m[k] == Approx(scalar.min_z_m[k]).margin(1e-4));
                }
                CHECK(same > 100);
                CHECK(differ <= 4);
            };
            agree(kernel, kernel_counters);
            agree(runs, run_counters);
        }
    }
}

TEST_CASE("the snapshot gives each cell's highest and lowest sample, NaN where unknown, through a wrap")
{
    for (const MapMode mode : {MapMode::egocentric, MapMode::world_aligned}) {
        INFO("mode " << static_cast<int>(mode));
        MapConfig c = base_config();
        c.mode = mode;
        TerrainMapper m(c);
        REQUIRE(m.add_pose(pose_at(0, 0.0, 0.0, 0.0)) == PoseHistory::AddResult::added);
        // A wall's cell: ground in front of it and the wall's face up to 1.5 m, all within
        // cell (row 10, column 75) of the egocentric map (x 2.0..2.2 m from the rear bumper).
        Points p;
        for (const float z : {0.0f, 0.25f, 1.5f, 0.75f, 0.05f}) p.add(-0.5f + 2.1f, 0.1f, z);
        p.add(-0.5f + 0.1f, 0.1f, -0.2f);  // row 0: driven over by the wrap below
        REQUIRE(m.fuse(p.batch(0)) == 6);
        MapSnapshot s;
        m.snapshot(s);
        const std::size_t wall = 10 * 150 + 75;
        CHECK(s.max_z_m[wall] == 1.5f);
        CHECK(s.min_z_m[wall] == 0.0f);
        CHECK(s.mean_z_m[wall] < 0.6f);  // the mean hides how tall it is
        CHECK(s.max_z_m[0 * 150 + 75] == -0.2f);
        CHECK(s.min_z_m[0 * 150 + 75] == -0.2f);
        int unknown = 0;
        for (std::size_t k = 0; k < s.count.size(); ++k) {
            if (s.count[k] != 0) continue;
            CHECK(std::isnan(s.max_z_m[k]));
            CHECK(std::isnan(s.min_z_m[k]));
            ++unknown;
        }
        // The world-aligned map is resampled by nearest cell: a world cell may show twice.
        CHECK(unknown >= 150 * 150 - (mode == MapMode::egocentric ? 2 : 4));
        CHECK(unknown <= 150 * 150 - 2);
        // One metre forward: five rows wrapped; the wall is now in row 5, row 0's cell gone.
        REQUIRE(m.add_pose(pose_at(1'000'000, 1.0, 0.0, 0.0)) == PoseHistory::AddResult::added);
        m.snapshot(s);
        CHECK(s.max_z_m[5 * 150 + 75] == 1.5f);
        CHECK(s.min_z_m[5 * 150 + 75] == 0.0f);
        int known = 0;
        for (std::size_t k = 0; k < s.count.size(); ++k) known += std::isnan(s.max_z_m[k]) ? 0 : 1;
        CHECK(known == 1);
    }
}

TEST_CASE("a cell's age is the map's time minus its newest sample's, NaN where unknown, through a wrap")
{
    for (const MapMode mode : {MapMode::egocentric, MapMode::world_aligned}) {
        INFO("mode " << static_cast<int>(mode));
        MapConfig c = base_config();
        c.mode = mode;
        TerrainMapper m(c);
        for (const int64_t t : {0, 1'000'000, 2'000'000, 2'500'000})
            REQUIRE(m.add_pose(pose_at(t, 0.0, 0.0, 0.0)) == PoseHistory::AddResult::added);
        // Cell a (row 10) at 1.0 s and again at 2.0 s; cell b (row 12) at 1.0 s only; row 0's
        // cell at 2.0 s. A batch within one scan's span takes its newest point's time (2.004 s).
        Points at_1, at_2;
        at_1.add(-0.5f + 2.1f, 0.1f, 0.0f);
        at_1.add(-0.5f + 2.5f, 0.1f, 0.0f);
        at_2.add(-0.5f + 2.1f, 0.1f, 0.0f, 0.01f, -0.002f);
        at_2.add(-0.5f + 0.1f, 0.1f, 0.0f, 0.01f, 0.004f);
        REQUIRE(m.fuse(at_1.batch(1'000'000)) == 2);
        REQUIRE(m.fuse(at_2.batch(2'000'000)) == 2);
        // Longer than max_interpolation_span_s: each point takes its own time (1.5 s, 2.5 s).
        Points spread_out;
        spread_out.add(-0.5f + 2.9f, 0.1f, 0.0f, 0.01f, -1.0f);
        spread_out.add(-0.5f + 3.3f, 0.1f, 0.0f, 0.01f, 0.0f);
        REQUIRE(m.fuse(spread_out.batch(2'500'000)) == 2);
        REQUIRE(m.add_pose(pose_at(3'500'000, 0.0, 0.0, 0.0)) == PoseHistory::AddResult::added);
        MapSnapshot s;
        m.snapshot(s);
        // The world-aligned map is resampled by nearest cell (a world cell may show twice or
        // not at all): there every known cell's age must be one of those fused.
        const std::vector<double> fused_at = {2.004, 1.0, 1.5, 2.5};
        std::vector<int> seen(fused_at.size());
        for (std::size_t k = 0; k < s.count.size(); ++k) {
            INFO("cell " << k);
            CHECK(std::isnan(s.age_s[k]) == (s.count[k] == 0));
            if (s.count[k] == 0) continue;
            std::size_t f = 0;
            while (f < fused_at.size() && std::abs(s.age_s[k] - (3.5 - fused_at[f])) > 1e-3) ++f;
            REQUIRE(f < fused_at.size());
            ++seen[f];
        }
        CHECK(std::count(seen.begin(), seen.end(), 0) <= (mode == MapMode::egocentric ? 0 : 1));
        if (mode == MapMode::egocentric) {
            CHECK(s.age_s[10 * 150 + 75] == Approx(3.5 - 2.004).margin(1e-3));  // a
            CHECK(s.age_s[12 * 150 + 75] == Approx(3.5 - 1.0).margin(1e-3));    // b
            CHECK(s.age_s[0 * 150 + 75] == Approx(3.5 - 2.004).margin(1e-3));
            CHECK(s.age_s[14 * 150 + 75] == Approx(3.5 - 1.5).margin(1e-3));
            CHECK(s.age_s[16 * 150 + 75] == Approx(3.5 - 2.5).margin(1e-3));
            CHECK(seen == std::vector<int>{2, 1, 1, 1});
        }
        // One metre forward at 4.5 s: five rows wrapped; row 0's cell is gone (NaN), a is in
        // row 5 and one second older.
        REQUIRE(m.add_pose(pose_at(4'500'000, 1.0, 0.0, 0.0)) == PoseHistory::AddResult::added);
        m.snapshot(s);
        CHECK(s.age_s[5 * 150 + 75] == Approx(4.5 - 2.004).margin(1e-3));
        if (mode == MapMode::egocentric) CHECK(s.age_s[7 * 150 + 75] == Approx(4.5 - 1.0).margin(1e-3));
        for (std::size_t k = 0; k < s.count.size(); ++k) CHECK(std::isnan(s.age_s[k]) == (s.count[k] == 0));
        for (std::size_t k = 0; k < 5 * 150; ++k) CHECK(std::isnan(s.age_s[k]));  // rows driven over
    }
}

// The tallies count milliseconds in 32 bits from an epoch the mapper moves on as the poses
// run (every 2^30 ms): the ages stay exact however long it runs.
TEST_CASE("ages stay exact over weeks of running")
{
    TerrainMapper m(base_config());
    const int64_t day_us = 86'400'000'000;
    REQUIRE(m.add_pose(pose_at(0, 0.0, 0.0, 0.0)) == PoseHistory::AddResult::added);
    Points p;
    p.add(-0.5f + 2.1f, 0.1f, 0.0f);
    REQUIRE(m.fuse(p.batch(0)) == 1);
    MapSnapshot s;
    const std::size_t cell = 10 * 150 + 75, other = 12 * 150 + 75;
    Points q;
    q.add(-0.5f + 2.5f, 0.1f, 0.0f);
    for (int day = 1; day <= 30; ++day) {
        const int64_t t = day * day_us + 123'000;
        REQUIRE(m.add_pose(pose_at(t, 0.0, 0.0, 0.0)) == PoseHistory::AddResult::added);
        REQUIRE(m.fuse(q.batch(t)) == 1);
        REQUIRE(m.add_pose(pose_at(t + 250'000, 0.0, 0.0, 0.0)) == PoseHistory::AddResult::added);
        m.snapshot(s);
        INFO("day " << day);
        CHECK(s.age_s[other] == Approx(0.25).margin(1e-3));
        // The first cell's time leaves the 32-bit range after 24.8 days: it then reads as at
        // least that old.
        const double age = static_cast<double>(t + 250'000) * 1e-6;
        if (age < 24.8 * 86'400.0)
            CHECK(s.age_s[cell] == Approx(age).epsilon(1e-6));
        else
            CHECK(s.age_s[cell] >= 24.8 * 86'400.0);
    }
}
