// The terrain mapper: poses move the map (wrap, rotate, follow), points are fused into it.
// The report's TerrainPose (checkScrollMap) is add_pose(); its TerrainMap (makeMap) is
// fuse(); its integrateData is snapshot(). No I/O, no middleware: the daemon adapts.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

#include <Eigen/Core>

#include "ugv/terrain/cell_tally.hpp"
#include "ugv/terrain/egocentric_grid.hpp"
#include "ugv/terrain/map_config.hpp"
#include "ugv/terrain/map_state.hpp"
#include "ugv/terrain/pose_history.hpp"
#include "ugv/terrain/world_grid.hpp"

namespace ugv::terrain {

namespace detail {
struct PlacedPoints;  // the fusion loop's scratch (src/kernels/fusion_kernels.hpp)
template <int K>
class SpreadSumsOf;  // section 3.5 spreading in summed-area form (src/spread_sums.hpp)
}

// One batch of points in the body frame (a view; the arrays hold count values each).
struct PointBatch
{
    int64_t utime_us = 0;                 // point k was measured at utime_us + time_offset_s[k]
    std::size_t count = 0;
    const float* x_m = nullptr;           // body frame
    const float* y_m = nullptr;
    const float* z_m = nullptr;
    const float* range_m = nullptr;       // r of eq. 19
    const float* variance_m2 = nullptr;   // sensor part of the variance
    const float* time_offset_s = nullptr;
};

struct MapCounters
{
    uint64_t points_fused = 0;
    uint64_t points_spread = 0;              // fused over several cells (section 3.5)
    uint64_t rejected_non_finite = 0;        // a NaN/Inf coordinate, range, variance or time
    uint64_t rejected_before_history = 0;    // older than the pose history
    uint64_t rejected_after_history = 0;     // newer than the newest pose
    uint64_t rejected_no_pose = 0;           // no pose received yet
    uint64_t rejected_outside_map = 0;       // outside the map's extent (never wrapped in)
    uint64_t poses_rejected_non_finite = 0;
    uint64_t poses_rejected_out_of_order = 0;
    uint64_t wraps = 0;                      // rows wrapped (egocentric) or rows+columns followed (world)
    uint64_t rotations = 0;                  // map rotations (egocentric)
    uint64_t recentres = 0;                  // lateral re-centring by whole columns (egocentric)
    uint64_t resets = 0;                     // map cleared after a pose jump larger than the map
    uint64_t cells_dropped = 0;              // cells rotated out of the map
    uint64_t cells_restored = 0;             // known cells taken from a saved map at the first pose

    template <class F>
    void visit(F&& f) const
    {
        f("points_fused", points_fused);
        f("points_spread", points_spread);
        f("rejected_non_finite", rejected_non_finite);
        f("rejected_before_history", rejected_before_history);
        f("rejected_after_history", rejected_after_history);
        f("rejected_no_pose", rejected_no_pose);
        f("rejected_outside_map", rejected_outside_map);
        f("poses_rejected_non_finite", poses_rejected_non_finite);
        f("poses_rejected_out_of_order", poses_rejected_out_of_order);
        f("wraps", wraps);
        f("rotations", rotations);
        f("recentres", recentres);
        f("resets", resets);
        f("cells_dropped", cells_dropped);
        f("cells_restored", cells_restored);
    }
};

// What the map says, in unwrapped order (i along the map's +X, j along +Y), ready to publish.
// The tally layers (count, max and min height: cell_tally.hpp) come from the base.
struct MapSnapshot : TallyLayers
{
    Pose pose;                    // the pose the map is referenced to
    double resolution_m = 0.0;
    int nx = 0, ny = 0;
    double origin_x_m = 0.0;      // corner of cell (0,0) from the body origin, along the map axes
    double origin_y_m = 0.0;
    int wrap_index = 0;           // m_i
    double x_curr_m = 0.0;        // forward motion not yet wrapped
    double residual_yaw_rad = 0.0;  // vehicle yaw minus map yaw (|.| < theta_d)
    MapMode mode = MapMode::egocentric;
    StatisticsKind statistics = StatisticsKind::variance_weighted;
    std::vector<float> mean_z_m;  // NaN = unknown
    std::vector<float> variance_z_m2;
};

// What became of a saved map given to restore_at_first_pose().
enum class RestoreOutcome : int8_t {
    none,      // none was given
    pending,   // waiting for the first pose
    restored,  // the map holds its cells again, moved by the first pose as by any pose
    moved,     // the first pose was further than the map's extent from it: dropped
    mismatch,  // another layout, statistics, reference point or mode: dropped
};

// Sums over every cell, ENU heights (for tests of conservation).
struct MapTotals
{
    uint64_t n = 0;    // samples (a spread point counts in every cell it touches)
    double w = 0.0;    // sum 1/s^2
    double w_z = 0.0;  // sum z/s^2
};

class TerrainMapper
{
public:
    // Throws std::invalid_argument for an invalid configuration.
    explicit TerrainMapper(const MapConfig& config);
    ~TerrainMapper();
    TerrainMapper(TerrainMapper&&) noexcept;
    TerrainMapper& operator=(TerrainMapper&&) noexcept;

    const MapConfig& config() const { return config_; }
    const MapCounters& counters() const { return counters_; }
    const PoseHistory& poses() const { return history_; }
    bool has_pose() const { return !history_.empty(); }

    // A new pose: kept in the history; the map translates (wrap) and rotates with it.
    PoseHistory::AddResult add_pose(const Pose& pose);
    // Fuses every valid point with the pose at its own time; returns the number fused.
    // No allocation and no whole-map pass.
    std::size_t fuse(const PointBatch& batch);
    // The map as it stands, referenced to the newest pose (reuses out's buffers).
    void snapshot(MapSnapshot& out) const;
    // The statistics of the cell that holds body-frame point (x, y) now, NaN when unknown
    // or outside (for tests and evaluation).
    CellStatistics statistics_at_body(double x_m, double y_m) const;
    // The sums of all cells (total weight, for tests of conservation).
    MapTotals total() const;

    void clear();

    // The pending spread shares (section 3.5, summed-area form) into the cells. The map does
    // this itself before it moves or is read; public for benchmarks that pace it. Const:
    // what the map says does not change, only where its sums are kept.
    void flush_spread() const;

    // The map's content and where it lies (egocentric mode, once a pose has placed it and
    // any restore was decided); false otherwise, and out is left as it was.
    bool save_state(MapState& out) const;
    // A saved map, decided at the first pose: restored when that pose's reference point is
    // within the map's extent of the saved map's (max of extent_x, extent_y, the same bound
    // as a pose jump's reset), else dropped.
    void restore_at_first_pose(MapState state);
    RestoreOutcome restore_outcome() const { return restore_outcome_; }
    // How far the first pose was from the saved map (m; NaN before the decision).
    double restore_distance_m() const { return restore_distance_m_; }

private:
    void decide_restore(const Pose& first);
    void discard_spread();  // the pending shares dropped (the map is cleared)
    struct Frame;
    Frame local_frame() const;
    void move_egocentric(const Pose& pose);
    void move_world(const Pose& pose);
    // split: a batch spanning more than max_interpolation_span_s is fused in runs that do not.
    template <typename Grid>
    std::size_t fuse_into(Grid& grid, const PointBatch& batch, bool split);
    template <typename Grid>
    void fuse_point(Grid& grid, float x, float y, double z, float variance_m2, TimeTick t_ms);
    // Section 3.5: spread_point adds the point to the pending summed-area corners of
    // config.spread_form (or, with SpreadForm::exact, runs spread_exact); spread_exact splats
    // it cell by cell, the readable reference the summed-area forms are tested against.
    template <typename Grid>
    void spread_point(Grid& grid, float x, float y, double z, float variance_m2, float w, TimeTick t_ms);
    template <typename Sums, typename Grid>
    void spread_summed(Sums& sums, Grid& grid, float x, float y, double z, float variance_m2, float w, TimeTick t_ms);
    template <typename Grid>
    void spread_exact(Grid& grid, float x, float y, double z, float variance_m2, float w, TimeTick t_ms);
    Eigen::Vector2d reference_world(const Pose& pose) const;
    // A time on the tallies' clock (whole ms since epoch_us_).
    TimeTick tick_of(int64_t utime_us) const;
    void rebase_ticks();

    MapConfig config_;
    PoseHistory history_;
    MapCounters counters_;
    int64_t epoch_us_ = 0;      // the tallies' times count from here (set by the first pose)
    bool has_epoch_ = false;
    std::unique_ptr<EgocentricGrid> ego_;
    std::unique_ptr<WorldGrid> world_;
    bool anchored_ = false;
    Eigen::Vector2d anchor_m_{0, 0};  // egocentric: ENU of the local frame's origin
    double anchor_yaw_rad_ = 0.0;     // egocentric: ENU yaw of the local X axis
    std::unique_ptr<detail::PlacedPoints> placed_;  // allocated once: fuse() allocates nothing
    std::unique_ptr<detail::SpreadSumsOf<8>> spread_sums_;     // with spread, SpreadForm::summed_area
    std::unique_ptr<detail::SpreadSumsOf<4>> spread_centred_;  // with spread, SpreadForm::centred
    std::unique_ptr<MapState> pending_restore_;
    RestoreOutcome restore_outcome_ = RestoreOutcome::none;
    double restore_distance_m_ = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace ugv::terrain
