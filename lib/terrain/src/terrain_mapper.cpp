#include "ugv/terrain/terrain_mapper.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "cell_fusion.hpp"
#include "kernels/kernel_table.hpp"
#include "spread_sums.hpp"
#include "ugv/geometry/rotation.hpp"
#include "ugv/terrain/point_variance.hpp"
#include "ugv/terrain/spread.hpp"

namespace ugv::terrain {

namespace {

using geometry::wrap_angle;
using geometry::rotation_2d;

// Body -> local map frame for one pose: rows 0-1 the local x, y; row 2 the ENU height.
struct Affine
{
    float a[9];
    float b[3];
};

Affine body_to_local(const Pose& pose, const Eigen::Vector2d& origin_m, double yaw_rad)
{
    Eigen::Matrix3d turn = Eigen::Matrix3d::Identity();
    turn.topLeftCorner<2, 2>() = rotation_2d(-yaw_rad);
    const Eigen::Matrix3d r = turn * pose.orientation.toRotationMatrix();
    Eigen::Vector3d t = pose.position_m;
    t.x() -= origin_m.x();
    t.y() -= origin_m.y();
    t = turn * t;
    Affine f;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) f.a[i * 3 + j] = static_cast<float>(r(i, j));
        f.b[i] = static_cast<float>(t(i));
    }
    return f;
}

// True when every value is finite: x * 0 is 0 for a finite x and NaN otherwise.
inline bool all_finite(float a, float b, float c, float d, float e, float f)
{
    // No std::isfinite: this form vectorises.
    return (a * 0.0f + b * 0.0f + c * 0.0f + d * 0.0f + e * 0.0f + f * 0.0f) == 0.0f;
}

constexpr float kNanF = std::numeric_limits<float>::quiet_NaN();

// The grids' ring layouts for place_points: the egocentric grid wraps its rows by m_i
// (eq. 6) and its columns by m_j, the world grid both axes by its own.
void set_ring(detail::Placement& p, const EgocentricGrid& g)
{
    p.row_shift = detail::splat(static_cast<float>(g.wrap_index()));
    p.ring_rows = detail::splat(static_cast<float>(g.nx()));
    p.column_shift = detail::splat(static_cast<float>(g.column_index()));
    p.ring_columns = detail::splat(static_cast<float>(g.ny()));
    p.row_stride = detail::splat(static_cast<float>(g.ny()));
}

void set_ring(detail::Placement& p, const WorldGrid& g)
{
    p.row_shift = detail::splat(static_cast<float>(g.ring_row()));
    p.ring_rows = detail::splat(static_cast<float>(g.size()));
    p.column_shift = detail::splat(static_cast<float>(g.ring_column()));
    p.ring_columns = detail::splat(static_cast<float>(g.size()));
    p.row_stride = detail::splat(static_cast<float>(g.size()));
}

}  // namespace

struct TerrainMapper::Frame
{
    Eigen::Vector2d origin_m;  // ENU of the local frame's origin
    double yaw_rad;            // ENU yaw of the local X axis
};

TerrainMapper::TerrainMapper(const MapConfig& config)
    : config_(config), history_(config.pose_history_us), placed_(std::make_unique<detail::PlacedPoints>())
{
    config_.validate();
    if (config_.mode == MapMode::egocentric) {
        ego_ = std::make_unique<EgocentricGrid>(config_.nx(), config_.ny(), config_.grid_size_m);
    } else {
        // The window must hold the forward extent in every direction the vehicle may face.
        const double side_m = 2.0 * std::max(config_.extent_x_m, 0.5 * config_.extent_y_m);
        world_ = std::make_unique<WorldGrid>(static_cast<int>(std::ceil(side_m / config_.grid_size_m)),
                                             config_.grid_size_m);
    }
    const int rows = ego_ ? ego_->nx() : world_->nx(), columns = ego_ ? ego_->ny() : world_->ny();
    if (config_.spread && config_.spread_form == SpreadForm::summed_area)
        spread_sums_ = std::make_unique<detail::SpreadSums>(rows, columns);
    if (config_.spread && config_.spread_form == SpreadForm::centred)
        spread_centred_ = std::make_unique<detail::SpreadSumsCentred>(rows, columns);
}

void TerrainMapper::flush_spread() const
{
    auto flush = [this](auto& sums) {
        if (!sums || !sums->pending()) return;
        if (ego_)
            sums->flush(*ego_);
        else
            sums->flush(*world_);
    };
    flush(spread_sums_);
    flush(spread_centred_);
}

void TerrainMapper::discard_spread()
{
    if (spread_sums_) spread_sums_->discard();
    if (spread_centred_) spread_centred_->discard();
}

TerrainMapper::~TerrainMapper() = default;
TerrainMapper::TerrainMapper(TerrainMapper&&) noexcept = default;
TerrainMapper& TerrainMapper::operator=(TerrainMapper&&) noexcept = default;

void TerrainMapper::clear()
{
    discard_spread();
    if (ego_) ego_->clear();
    if (world_) world_->clear();
    history_.clear();
    anchored_ = false;
    has_epoch_ = false;  // no cell holds a time any more
}

TimeTick TerrainMapper::tick_of(int64_t utime_us) const
{
    // Within range by construction (points lie within the pose history, and rebase_ticks
    // keeps the newest pose within 2^30 ms of the epoch); the clamp keeps kNoTime out.
    const long long ms = std::llround(static_cast<double>(utime_us - epoch_us_) * 1e-3);
    return static_cast<TimeTick>(std::clamp<long long>(ms, kNoTime + 1LL, std::numeric_limits<TimeTick>::max()));
}

void TerrainMapper::rebase_ticks()
{
    // Before the newest pose is 2^30 ms (12.4 days) past the epoch, move the epoch to it
    // and every cell's time with it (a whole-map pass every 12 days); a time that would
    // fall below the range reads as the oldest one (an age of at least 24.8 days).
    constexpr int64_t kLimitUs = (int64_t{1} << 30) * 1000;
    const int64_t newest = history_.newest().utime_us;
    if (newest - epoch_us_ < kLimitUs) return;
    flush_spread();  // the pending shares' time is on the old epoch
    const int64_t shift_ms = (newest - epoch_us_) / 1000;
    epoch_us_ += shift_ms * 1000;
    CellArray& cells = ego_ ? ego_->cells() : world_->cells();
    CellTally* t = cells.tallies_data();
    for (std::size_t k = 0; k < cells.size(); ++k) {
        if (t[k].newest_ms == kNoTime) continue;
        t[k].newest_ms = static_cast<TimeTick>(std::max<int64_t>(t[k].newest_ms - shift_ms, kNoTime + 1LL));
    }
}

Eigen::Vector2d TerrainMapper::reference_world(const Pose& pose) const
{
    return pose.position_m.head<2>() + rotation_2d(pose.yaw_rad()) * Eigen::Vector2d(config_.reference_x_m, config_.reference_y_m);
}

TerrainMapper::Frame TerrainMapper::local_frame() const
{
    if (ego_) return {anchor_m_, anchor_yaw_rad_};
    return {world_->corner_m(), 0.0};
}

PoseHistory::AddResult TerrainMapper::add_pose(const Pose& pose)
{
    const auto result = history_.add(pose);
    if (result == PoseHistory::AddResult::non_finite) {
        ++counters_.poses_rejected_non_finite;
        return result;
    }
    if (result == PoseHistory::AddResult::out_of_order) {
        ++counters_.poses_rejected_out_of_order;
        return result;
    }
    if (!has_epoch_) {
        epoch_us_ = history_.newest().utime_us;
        has_epoch_ = true;
    }
    rebase_ticks();
    if (pending_restore_) decide_restore(history_.newest());
    if (ego_) {
        move_egocentric(history_.newest());
    } else {
        move_world(history_.newest());
    }
    return result;
}

void TerrainMapper::move_egocentric(const Pose& pose)
{
    const Eigen::Vector2d ref = reference_world(pose);
    const double yaw = pose.yaw_rad();
    if (!anchored_) {
        anchored_ = true;
        anchor_m_ = ref;
        anchor_yaw_rad_ = yaw;
        return;
    }
    Eigen::Vector2d local = rotation_2d(-anchor_yaw_rad_) * (ref - anchor_m_);
    if (local.norm() > std::max(config_.extent_x_m, config_.extent_y_m)) {
        // A jump larger than the map (GPS reacquired, datum change): nothing in it still holds.
        discard_spread();
        ego_->clear();
        anchor_m_ = ref;
        anchor_yaw_rad_ = yaw;
        ++counters_.resets;
        return;
    }
    const double g = config_.grid_size_m;
    // Rotation (section 3.3.2): once the summed yaw passes theta_d, turn the map by the whole
    // multiples of theta_d it holds, about the reference point, which becomes the new origin.
    const double d_yaw = wrap_angle(yaw - anchor_yaw_rad_);
    if (std::abs(d_yaw) >= config_.theta_d_rad) {
        const double steps = std::trunc(d_yaw / config_.theta_d_rad);
        const double angle = steps * config_.theta_d_rad;
        flush_spread();
        counters_.cells_dropped += static_cast<uint64_t>(ego_->transform(angle, local.x(), local.y()));
        anchor_m_ = ref;
        anchor_yaw_rad_ = wrap_angle(anchor_yaw_rad_ + angle);
        ++counters_.rotations;
        local.setZero();
    }
    // Translation (eq. 5-8 as corrected in docs/ARCHITECTURE.md, "Corrections to the
    // report's equations"): the motion projected on the map's heading accumulates in
    // x_curr; wrap as many whole rows as it holds, keep the rest.
    // The 1 nm tolerance keeps exactly k cells of travel from rounding to k - 1.
    const Eigen::Vector2d ex(std::cos(anchor_yaw_rad_), std::sin(anchor_yaw_rad_));
    const Eigen::Vector2d ey(-ex.y(), ex.x());
    const int rows = static_cast<int>(std::floor(local.x() / g + 1e-9));
    if (rows != 0) flush_spread();
    if (rows > 0) ego_->wrap_forward(rows);
    if (rows < 0) ego_->wrap_backward(-rows);
    if (rows != 0) {
        anchor_m_ += rows * g * ex;
        counters_.wraps += static_cast<uint64_t>(std::abs(rows));
    }
    // Sideways motion (sideslip, or driving with a residual yaw) does not advance the map;
    // once it adds up to whole columns the map is re-centred on the vehicle.
    // A ring index like the rows' (shift_columns), not a transform: no cell moves.
    const int columns = static_cast<int>(std::trunc(local.y() / g + (local.y() > 0 ? 1e-9 : -1e-9)));
    if (columns != 0) {
        flush_spread();
        counters_.cells_dropped += static_cast<uint64_t>(ego_->shift_columns(columns));
        anchor_m_ += columns * g * ey;
        ++counters_.recentres;
    }
}

void TerrainMapper::restore_at_first_pose(MapState state)
{
    if (!history_.empty()) {  // too late: the map is already somewhere
        restore_outcome_ = RestoreOutcome::mismatch;
        return;
    }
    pending_restore_ = std::make_unique<MapState>(std::move(state));
    restore_outcome_ = RestoreOutcome::pending;
}

void TerrainMapper::decide_restore(const Pose& first)
{
    const std::unique_ptr<MapState> s = std::move(pending_restore_);
    if (!ego_ || s->nx != config_.nx() || s->ny != config_.ny() || s->grid_size_m != config_.grid_size_m ||
        s->statistics != config_.statistics || s->reference_x_m != config_.reference_x_m ||
        s->reference_y_m != config_.reference_y_m) {
        restore_outcome_ = RestoreOutcome::mismatch;
        return;
    }
    const Eigen::Vector2d anchor(s->anchor_x_m, s->anchor_y_m);
    restore_distance_m_ = (rotation_2d(-s->anchor_yaw_rad) * (reference_world(first) - anchor)).norm();
    if (!(restore_distance_m_ <= std::max(config_.extent_x_m, config_.extent_y_m))) {
        restore_outcome_ = RestoreOutcome::moved;
        return;
    }
    ego_->clear();  // unwrapped index = physical index while m_i = 0
    // The saved times onto this mapper's clock; none newer than the first pose (a file
    // from a clock that ran ahead reads as just seen, never as from the future).
    const int64_t shift_ms = std::llround(static_cast<double>(s->epoch_us - epoch_us_) * 1e-3);
    const int64_t now_ms = tick_of(first.utime_us);
    for (const SavedCell& c : s->cells) {
        const auto slot = static_cast<int>(ego_->storage_of(static_cast<int>(c.index)));
        ego_->cells().sums(slot) = c.sums;
        CellTally& t = ego_->cells().tally(slot);
        t = c.tally;
        t.newest_ms = static_cast<TimeTick>(std::clamp<int64_t>(c.tally.newest_ms + shift_ms, kNoTime + 1LL, now_ms));
    }
    anchored_ = true;
    anchor_m_ = anchor;
    anchor_yaw_rad_ = s->anchor_yaw_rad;
    counters_.cells_restored += s->cells.size();
    restore_outcome_ = RestoreOutcome::restored;
}

bool TerrainMapper::save_state(MapState& out) const
{
    if (!ego_ || !anchored_ || pending_restore_) return false;
    flush_spread();
    const int nx = config_.nx(), ny = config_.ny();
    out.nx = nx;
    out.ny = ny;
    out.grid_size_m = config_.grid_size_m;
    out.statistics = config_.statistics;
    out.reference_x_m = config_.reference_x_m;
    out.reference_y_m = config_.reference_y_m;
    out.anchor_x_m = anchor_m_.x();
    out.anchor_y_m = anchor_m_.y();
    out.anchor_yaw_rad = anchor_yaw_rad_;
    out.utime_us = history_.empty() ? 0 : history_.newest().utime_us;
    out.epoch_us = epoch_us_;
    out.cells.clear();
    for (int i = 0; i < nx; ++i)
        for (int j = 0; j < ny; ++j) {
            const CellSums& c = ego_->at(i, j);
            const CellTally& t = ego_->tally(i, j);
            if (c.empty() || t.count == 0) continue;
            out.cells.push_back({static_cast<uint32_t>(i * ny + j), c, t});
        }
    return true;
}

void TerrainMapper::move_world(const Pose& pose)
{
    flush_spread();
    counters_.wraps += static_cast<uint64_t>(world_->follow(reference_world(pose)));
}

template <typename Grid>
void TerrainMapper::spread_point(Grid& grid, float x, float y, double z, float variance_m2, float w, TimeTick t_ms)
{
    if (spread_sums_)
        spread_summed(*spread_sums_, grid, x, y, z, variance_m2, w, t_ms);
    else if (spread_centred_)
        spread_summed(*spread_centred_, grid, x, y, z, variance_m2, w, t_ms);
    else
        spread_exact(grid, x, y, z, variance_m2, w, t_ms);
}

template <typename Sums, typename Grid>
void TerrainMapper::spread_summed(Sums& sums, Grid& grid, float x, float y, double z, float variance_m2, float w,
                                  TimeTick t_ms)
{
    const float inv_g = static_cast<float>(1.0 / config_.grid_size_m);
    const float half_width = std::min(std::sqrt(variance_m2) * inv_g, static_cast<float>(config_.spread_max_cells));
    if (!sums.add(x * inv_g, (y - static_cast<float>(grid.y_min_m())) * inv_g, half_width, w,
                  static_cast<float>(config_.grid_size_m), static_cast<float>(z), t_ms)) {
        ++counters_.rejected_outside_map;
        return;
    }
    ++counters_.points_fused;
    ++counters_.points_spread;
}

template <typename Grid>
void TerrainMapper::spread_exact(Grid& grid, float x, float y, double z, float variance_m2, float w, TimeTick t_ms)
{
    const float inv_g = static_cast<float>(1.0 / config_.grid_size_m);
    const float g = static_cast<float>(config_.grid_size_m);
    const float half_width = std::min(std::sqrt(variance_m2) * inv_g, static_cast<float>(config_.spread_max_cells));
    const AxisFootprint fx = axis_footprint(x * inv_g, half_width, grid.nx());
    const AxisFootprint fy = axis_footprint((y - static_cast<float>(grid.y_min_m())) * inv_g, half_width, grid.ny());
    if (fx.count == 0 || fy.count == 0) {
        ++counters_.rejected_outside_map;
        return;
    }
    const detail::CellArrays cells(grid.cells());
    const float z_f = static_cast<float>(z);
    // The cell the point was measured in (none when it lies off the map's edge).
    const int own_row = static_cast<int>(std::floor(x * inv_g));
    const int own_column = static_cast<int>(std::floor((y - static_cast<float>(grid.y_min_m())) * inv_g));
    for (int a = 0; a < fx.count; ++a) {
        for (int b = 0; b < fy.count; ++b) {
            const int row = fx.first + a, column = fy.first + b;
            const uint32_t at = grid.storage_of(grid.physical(row, column));
            alignas(16) float sample[4];
            detail::store4(sample, detail::Float4{0.0f, fx.centre[a] * g, fy.centre[b] * g, z_f});
            const float share = w * fx.fraction[a] * fy.fraction[b];
            if (row == own_row && column == own_column) {
                cells.add_placed(at, sample, share, t_ms);
                continue;
            }
            // A share in a neighbour moves its mean by its weight, but its height was not
            // measured there: it is counted (and dates the cell), not put in the neighbour's
            // max/min, so a box's top spread beside the box (a large sigma: far range, a poor
            // yaw) is no ghost obstacle.
            detail::fuse_point_into(cells.sums[at], sample, share);
            CellTally& tally = cells.tallies[at];
            ++tally.count;
            tally.newest_ms = tally.newest_ms > t_ms ? tally.newest_ms : t_ms;
        }
    }
    ++counters_.points_fused;
    ++counters_.points_spread;
}

template <typename Grid>
inline void TerrainMapper::fuse_point(Grid& grid, float x, float y, double z, float variance_m2, TimeTick t_ms)
{
    variance_m2 = std::max(variance_m2, static_cast<float>(config_.min_variance_m2));
    const float w = config_.statistics == StatisticsKind::classical ? 1.0f : 1.0f / variance_m2;
    if (config_.spread && variance_m2 > static_cast<float>(config_.grid_size_m * config_.grid_size_m)) {
        spread_point(grid, x, y, z, variance_m2, w, t_ms);
        return;
    }
    float x_rel = 0.0f, y_rel = 0.0f;
    const int cell = grid.locate(x, y, x_rel, y_rel);
    if (cell < 0) {
        ++counters_.rejected_outside_map;
        return;
    }
    grid.fuse(cell, x_rel, y_rel, z, w, t_ms);
    ++counters_.points_fused;
}

template <typename Grid>
std::size_t TerrainMapper::fuse_into(Grid& grid, const PointBatch& batch, bool split)
{
    const uint64_t fused_before = counters_.points_fused;
    const std::size_t n = batch.count;
    if (history_.empty()) {
        counters_.rejected_no_pose += n;
        return 0;
    }
    // The batch's time span: the poses at its two ends bound every point's pose.
    float t_min = 0.0f, t_max = 0.0f;
    detail::value_range(batch.time_offset_s, n, t_min, t_max);
    if (split && config_.split_long_batches && t_min <= t_max && t_max - t_min > config_.max_interpolation_span_s) {
        // A long batch (a slow scan, a lidar's sweep, clouds joined) in runs of consecutive
        // points each spanning at most max_interpolation_span_s, each fused as one batch.
        // A point whose time is not finite joins the run it is in; the run then spans an
        // infinity and goes point by point, which rejects it.
        std::size_t first = 0;
        float lo = std::numeric_limits<float>::infinity(), hi = -lo;
        auto run = [&](std::size_t end) {
            PointBatch part = batch;
            part.count = end - first;
            for (const float** a : {&part.x_m, &part.y_m, &part.z_m, &part.range_m, &part.variance_m2, &part.time_offset_s})
                *a += first;
            fuse_into(grid, part, false);
            first = end;
        };
        for (std::size_t k = 0; k < n; ++k) {
            const float t = batch.time_offset_s[k];
            if (!(std::abs(t) <= std::numeric_limits<float>::max())) continue;
            const float new_lo = std::min(lo, t), new_hi = std::max(hi, t);
            if (static_cast<double>(new_hi - new_lo) > config_.max_interpolation_span_s) {  // as the run's own test
                run(k);
                lo = hi = t;
            } else {
                lo = new_lo;
                hi = new_hi;
            }
        }
        run(n);
        return static_cast<std::size_t>(counters_.points_fused - fused_before);
    }
    const Frame frame = local_frame();
    Pose p0, p1;
    const int64_t t_max_us = t_min <= t_max ? batch.utime_us + std::llround(t_max * 1e6) : 0;
    const bool fast = t_min <= t_max && t_max - t_min <= config_.max_interpolation_span_s &&
                      history_.at(batch.utime_us + std::llround(t_min * 1e6), p0) == PoseHistory::Lookup::ok &&
                      history_.at(t_max_us, p1) == PoseHistory::Lookup::ok;
    if (fast) {
        // Every sample of the batch takes the batch's newest time: within the span above
        // (one scan) of its own, and the vector kernels need not carry times.
        const TimeTick batch_ms = tick_of(t_max_us);
        // Over a scan (13-27 ms) the transform changes by a small rotation: blending the two
        // end transforms linearly is within (d_angle^2)/8 of the slerp, < 0.1 mm at 30 m
        // for 1 rad/s, and exact at the ends. The eq. 19 orientation error blends likewise.
        const Affine a0 = body_to_local(p0, frame.origin_m, frame.yaw_rad);
        const Affine a1 = body_to_local(p1, frame.origin_m, frame.yaw_rad);
        detail::Placement placement;
        for (int row = 0; row < 3; ++row) {
            for (int c = 0; c < 4; ++c) {
                const float start = c < 3 ? a0.a[row * 3 + c] : a0.b[row];
                const float end = c < 3 ? a1.a[row * 3 + c] : a1.b[row];
                placement.at_start[4 * row + c] = detail::splat(start);
                placement.change[4 * row + c] = detail::splat(end - start);
            }
        }
        const float de0 = static_cast<float>(p0.orientation_error_rad2());
        placement.t_min_s = detail::splat(t_min);
        placement.inv_span_per_s = detail::splat(t_max > t_min ? 1.0f / (t_max - t_min) : 0.0f);
        placement.error_at_start_rad2 = detail::splat(de0);
        placement.error_change_rad2 = detail::splat(static_cast<float>(p1.orientation_error_rad2()) - de0);
        placement.min_variance_m2 = detail::splat(static_cast<float>(config_.min_variance_m2));
        // Classical statistics fuse with unit weight: w = 0 / s2 + 1.
        const bool classical = config_.statistics == StatisticsKind::classical;
        placement.inverse_scale = detail::splat(classical ? 0.0f : 1.0f);
        placement.unit_weight = detail::splat(classical ? 1.0f : 0.0f);
        const float spread_above = config_.spread ? static_cast<float>(config_.grid_size_m * config_.grid_size_m)
                                                  : std::numeric_limits<float>::infinity();
        placement.spread_above_m2 = detail::splat(spread_above);
        const float g = static_cast<float>(config_.grid_size_m);
        const float nx_f = static_cast<float>(grid.nx()), ny_f = static_cast<float>(grid.ny());
        placement.inv_g = detail::splat(1.0f / g);
        placement.g = detail::splat(g);
        placement.y_min_m = detail::splat(static_cast<float>(grid.y_min_m()));
        placement.nx = detail::splat(nx_f);
        placement.ny = detail::splat(ny_f);
        placement.nx_last = detail::splat(nx_f - 0.5f);
        placement.ny_last = detail::splat(ny_f - 0.5f);
        set_ring(placement, grid);
        // Chunks of points, two passes each: place_chunk (branch-free, 4 or 8 points at a time),
        // then the sums. Only the rare points (invalid, outside, spread) take a branch.
        constexpr std::size_t kChunk = detail::PlacedPoints::kCapacity;
        const detail::PlaceChunk place_chunk = detail::kernels().place_chunk;
        detail::PlacedPoints& placed = *placed_;
        uint64_t fused = 0, non_finite = 0, outside = 0;
        const detail::CellArrays cells(grid.cells());
        for (std::size_t base = 0; base < n; base += kChunk) {
            const std::size_t count = std::min(n - base, kChunk);
            const float* px = batch.x_m + base;
            const float* py = batch.y_m + base;
            const float* pz = batch.z_m + base;
            const float* pr = batch.range_m + base;
            const float* pv = batch.variance_m2 + base;
            const float* pt = batch.time_offset_s + base;
            const float* const in[6] = {px, py, pz, pr, pv, pt};
            place_chunk(placement, in, count, placed);
            int rare[kChunk];
            std::size_t rare_count = 0;
            auto add = [&](std::size_t q) {
                const uint32_t at = grid.storage_of(placed.cell[q]);
                cells.add_placed(at, placed.sample[q], placed.weight[q], batch_ms);
            };
            auto add_or_defer = [&](std::size_t q) {
                if (placed.fuse[q]) [[likely]]
                    add(q);
                else
                    rare[rare_count++] = static_cast<int>(q);
            };
            auto add_group = [&](std::size_t first) {
                if (placed.all_fuse[first / 4]) [[likely]] {
                    for (std::size_t q = first; q < first + 4; ++q) add(q);
                } else {
                    for (std::size_t q = first; q < first + 4; ++q) add_or_defer(q);
                }
            };
            // Groups of four plain points (nearly all) without a test per point. In a full
            // chunk the four quarters are interleaved: consecutive points of a scan often hit
            // the same cell, and a cell's next sum must wait for its last one (a store and a
            // reload); points 16 apart (8 degrees of a scan) rarely share a cell, so four
            // such chains overlap.
            std::size_t k = 0;
            if (count == kChunk) {
                constexpr std::size_t kQuarter = kChunk / 4;
                for (; k < kQuarter; k += 4) {
                    const bool plain = placed.all_fuse[k / 4] && placed.all_fuse[(k + kQuarter) / 4] &&
                                       placed.all_fuse[(k + 2 * kQuarter) / 4] && placed.all_fuse[(k + 3 * kQuarter) / 4];
                    if (plain) [[likely]] {
                        for (std::size_t q = k; q < k + 4; ++q)
                            for (std::size_t part = 0; part < 4; ++part) add(q + part * kQuarter);
                    } else {
                        for (std::size_t part = 0; part < 4; ++part) add_group(k + part * kQuarter);
                    }
                }
                k = kChunk;
            }
            for (; k + 4 <= count; k += 4) add_group(k);
            for (; k < count; ++k) add_or_defer(k);
            fused += count - rare_count;
            // The rare points, in the order of the slow path: invalid, spread, outside.
            for (std::size_t q = 0; q < rare_count; ++q) {
                const int r = rare[q];
                if (!all_finite(px[r], py[r], pz[r], pr[r], pv[r], pt[r]) || pv[r] < 0.0f) {
                    ++non_finite;
                } else if (placed.variance_m2[r] > spread_above) {
                    spread_point(grid, placed.lx[r], placed.ly[r], placed.lz[r], placed.variance_m2[r],
                                 placed.weight[r], batch_ms);
                } else {
                    ++outside;
                }
            }
        }
        counters_.points_fused += fused;
        counters_.rejected_non_finite += non_finite;
        counters_.rejected_outside_map += outside;
    } else {
        // Slow path: each point looks up its own pose and is rejected by reason.
        for (std::size_t k = 0; k < n; ++k) {
            const float x = batch.x_m[k], y = batch.y_m[k], z = batch.z_m[k];
            const float r = batch.range_m[k], v = batch.variance_m2[k], t = batch.time_offset_s[k];
            if (!all_finite(x, y, z, r, v, t) || v < 0.0f) {
                ++counters_.rejected_non_finite;
                continue;
            }
            Pose p;
            const int64_t t_us = batch.utime_us + std::llround(static_cast<double>(t) * 1e6);
            const auto found = history_.at(t_us, p);
            if (found == PoseHistory::Lookup::before_history) {
                ++counters_.rejected_before_history;
                continue;
            }
            if (found != PoseHistory::Lookup::ok) {
                ++counters_.rejected_after_history;
                continue;
            }
            const Affine a = body_to_local(p, frame.origin_m, frame.yaw_rad);
            const float lx = a.a[0] * x + a.a[1] * y + a.a[2] * z + a.b[0];
            const float ly = a.a[3] * x + a.a[4] * y + a.a[5] * z + a.b[1];
            const float lz = a.a[6] * x + a.a[7] * y + a.a[8] * z + a.b[2];
            fuse_point(grid, lx, ly, lz, point_variance_m2(v, r, static_cast<float>(p.orientation_error_rad2())),
                       tick_of(t_us));
        }
    }
    return static_cast<std::size_t>(counters_.points_fused - fused_before);
}

std::size_t TerrainMapper::fuse(const PointBatch& batch)
{
    if (ego_) return fuse_into(*ego_, batch, true);
    return fuse_into(*world_, batch, true);
}

void TerrainMapper::snapshot(MapSnapshot& out) const
{
    flush_spread();
    const int nx = config_.nx(), ny = config_.ny();
    const double g = config_.grid_size_m;
    const std::size_t cells = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
    out.resolution_m = g;
    out.nx = nx;
    out.ny = ny;
    out.mode = config_.mode;
    out.statistics = config_.statistics;
    out.mean_z_m.assign(cells, kNanF);
    out.variance_z_m2.assign(cells, kNanF);
    out.reset(cells);
    const double y_min = -0.5 * ny * g;
    const double now_ms = history_.empty() ? 0.0 : static_cast<double>(history_.newest().utime_us - epoch_us_) * 1e-3;
    auto put = [&](std::size_t k, const CellSums& c, const CellTally& t) {
        if (c.empty()) return;
        const CellStatistics s = cell_statistics(c, config_.statistics);
        out.mean_z_m[k] = static_cast<float>(s.mean_z_m);
        out.variance_z_m2[k] = static_cast<float>(s.variance_z_m2);
        // Spread shares reach a cell's mean but not its extremes (spread_point): the extremes
        // shown include the mean, so min <= mean <= max holds and a cell holding shares only
        // is not left without them.
        CellTally shown = t;
        shown.extremes.add(out.mean_z_m[k]);
        out.put(k, shown, now_ms);
    };
    if (history_.empty()) {
        out.pose = Pose{};
        out.origin_x_m = config_.reference_x_m;
        out.origin_y_m = config_.reference_y_m + y_min;
        out.wrap_index = 0;
        out.x_curr_m = 0.0;
        out.residual_yaw_rad = 0.0;
        return;
    }
    const Pose& pose = history_.newest();
    out.pose = pose;
    const double yaw = pose.yaw_rad();
    if (ego_) {
        const Eigen::Vector2d body = rotation_2d(-anchor_yaw_rad_) * (pose.position_m.head<2>() - anchor_m_);
        const Eigen::Vector2d ref = rotation_2d(-anchor_yaw_rad_) * (reference_world(pose) - anchor_m_);
        out.origin_x_m = -body.x();
        out.origin_y_m = y_min - body.y();
        out.wrap_index = ego_->wrap_index();
        out.x_curr_m = ref.x();
        out.residual_yaw_rad = wrap_angle(yaw - anchor_yaw_rad_);
        for (int i = 0; i < nx; ++i)
            for (int j = 0; j < ny; ++j)
                put(static_cast<std::size_t>(i * ny + j), ego_->at(i, j), ego_->tally(i, j));
        return;
    }
    // World-aligned: resample into the vehicle's heading at the reference point (nearest cell).
    const Eigen::Vector2d ref = reference_world(pose);
    const Eigen::Matrix2d turn = rotation_2d(yaw);
    out.origin_x_m = config_.reference_x_m;
    out.origin_y_m = config_.reference_y_m + y_min;
    out.wrap_index = 0;
    out.x_curr_m = 0.0;
    out.residual_yaw_rad = 0.0;
    for (int i = 0; i < nx; ++i) {
        for (int j = 0; j < ny; ++j) {
            const Eigen::Vector2d local((i + 0.5) * g, y_min + (j + 0.5) * g);
            const int c = world_->cell_at(ref + turn * local);
            if (c >= 0) put(static_cast<std::size_t>(i * ny + j), world_->at(c), world_->tally(c));
        }
    }
}

CellStatistics TerrainMapper::statistics_at_body(double x_m, double y_m) const
{
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    flush_spread();
    if (history_.empty()) return {nan, nan};
    const Pose& pose = history_.newest();
    const Eigen::Vector2d world = pose.position_m.head<2>() + rotation_2d(pose.yaw_rad()) * Eigen::Vector2d(x_m, y_m);
    if (ego_) {
        const Eigen::Vector2d local = rotation_2d(-anchor_yaw_rad_) * (world - anchor_m_);
        float xr = 0, yr = 0;
        const int cell = ego_->locate(static_cast<float>(local.x()), static_cast<float>(local.y()), xr, yr);
        if (cell < 0) return {nan, nan};
        return cell_statistics(ego_->at(cell), config_.statistics);
    }
    const int c = world_->cell_at(world);
    if (c < 0) return {nan, nan};
    return cell_statistics(world_->at(c), config_.statistics);
}

MapTotals TerrainMapper::total() const
{
    flush_spread();
    MapTotals sum;
    auto add = [&sum](const CellSums& c, uint32_t n) {
        if (c.empty()) return;
        double wz = 0.0, wz2 = 0.0;
        z_sums_about(c, 0.0, wz, wz2);
        sum.n += n;
        sum.w += c.w;
        sum.w_z += wz;
    };
    if (ego_) {
        for (int i = 0; i < ego_->nx(); ++i)
            for (int j = 0; j < ego_->ny(); ++j) add(ego_->at(i, j), ego_->count(i, j));
    } else {
        const int n = world_->size();
        for (int k = 0; k < n * n; ++k) add(world_->at(k), world_->count(k));
    }
    return sum;
}

}  // namespace ugv::terrain
