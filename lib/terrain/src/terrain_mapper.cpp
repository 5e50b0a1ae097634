#include "ugv/terrain/terrain_mapper.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ugv/terrain/point_variance.hpp"
#include "ugv/terrain/spread.hpp"

namespace ugv::terrain {

namespace {

Eigen::Matrix2d rot2(double yaw)
{
    const double c = std::cos(yaw), s = std::sin(yaw);
    Eigen::Matrix2d r;
    r << c, -s, s, c;
    return r;
}

// Body -> local map frame for one pose: rows 0-1 the local x, y; row 2 the ENU height.
struct Affine
{
    float a[9];
    float b[3];
};

Affine body_to_local(const Pose& pose, const Eigen::Vector2d& origin_m, double yaw_rad)
{
    Eigen::Matrix3d turn = Eigen::Matrix3d::Identity();
    turn.topLeftCorner<2, 2>() = rot2(-yaw_rad);
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

}  // namespace

struct TerrainMapper::Frame
{
    Eigen::Vector2d origin_m;  // ENU of the local frame's origin
    double yaw_rad;            // ENU yaw of the local X axis
};

TerrainMapper::TerrainMapper(const MapConfig& config) : config_(config), history_(config.pose_history_us)
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
}

void TerrainMapper::clear()
{
    if (ego_) ego_->clear();
    if (world_) world_->clear();
    history_.clear();
    anchored_ = false;
}

Eigen::Vector2d TerrainMapper::reference_world(const Pose& pose) const
{
    return pose.position_m.head<2>() + rot2(pose.yaw_rad()) * Eigen::Vector2d(config_.reference_x_m, config_.reference_y_m);
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
    Eigen::Vector2d local = rot2(-anchor_yaw_rad_) * (ref - anchor_m_);
    if (local.norm() > std::max(config_.extent_x_m, config_.extent_y_m)) {
        // A jump larger than the map (GPS reacquired, datum change): nothing in it still holds.
        ego_->clear();
        anchor_m_ = ref;
        anchor_yaw_rad_ = yaw;
        ++counters_.resets;
        return;
    }
    const double g = config_.grid_size_m;
    // Rotation (section 3.3.2): once the summed yaw passes theta_d, turn the map by the whole
    // multiples of theta_d it holds, about the reference point, which becomes the new origin.
    const double d_yaw = wrap_angle_rad(yaw - anchor_yaw_rad_);
    if (std::abs(d_yaw) >= config_.theta_d_rad) {
        const double steps = std::trunc(d_yaw / config_.theta_d_rad);
        const double angle = steps * config_.theta_d_rad;
        counters_.cells_dropped += static_cast<uint64_t>(ego_->transform(angle, local.x(), local.y()));
        anchor_m_ = ref;
        anchor_yaw_rad_ = wrap_angle_rad(anchor_yaw_rad_ + angle);
        ++counters_.rotations;
        local.setZero();
    }
    // Translation (eq. 5-8 as corrected in DESIGN §7): the motion projected on the map's
    // heading accumulates in x_curr; wrap as many whole rows as it holds, keep the rest.
    // The 1 nm tolerance keeps exactly k cells of travel from rounding to k - 1.
    const Eigen::Vector2d ex(std::cos(anchor_yaw_rad_), std::sin(anchor_yaw_rad_));
    const Eigen::Vector2d ey(-ex.y(), ex.x());
    const int rows = static_cast<int>(std::floor(local.x() / g + 1e-9));
    if (rows > 0) ego_->wrap_forward(rows);
    if (rows < 0) ego_->wrap_backward(-rows);
    if (rows != 0) {
        anchor_m_ += rows * g * ex;
        counters_.wraps += static_cast<uint64_t>(std::abs(rows));
    }
    // Sideways motion (sideslip, or driving with a residual yaw) does not advance the map;
    // once it adds up to whole columns the map is re-centred on the vehicle.
    const int columns = static_cast<int>(std::trunc(local.y() / g + (local.y() > 0 ? 1e-9 : -1e-9)));
    if (columns != 0) {
        counters_.cells_dropped += static_cast<uint64_t>(ego_->transform(0.0, 0.0, columns * g));
        anchor_m_ += columns * g * ey;
        ++counters_.recentres;
    }
}

void TerrainMapper::move_world(const Pose& pose)
{
    counters_.wraps += static_cast<uint64_t>(world_->follow(reference_world(pose)));
}

template <typename Grid>
void TerrainMapper::spread_point(Grid& grid, int rows, int cols, float x, float y, double z, float variance_m2,
                                 float w)
{
    const float inv_g = static_cast<float>(1.0 / config_.grid_size_m);
    const float g = static_cast<float>(config_.grid_size_m);
    const float half_width = std::min(std::sqrt(variance_m2) * inv_g, static_cast<float>(config_.spread_max_cells));
    const AxisFootprint fx = axis_footprint(x * inv_g, half_width, rows);
    const AxisFootprint fy = axis_footprint((y - static_cast<float>(grid.y_min_m())) * inv_g, half_width, cols);
    if (fx.count == 0 || fy.count == 0) {
        ++counters_.rejected_outside_map;
        return;
    }
    for (int a = 0; a < fx.count; ++a) {
        for (int b = 0; b < fy.count; ++b) {
            CellSums& cell = grid.at(grid.physical(fx.first + a, fy.first + b));
            fuse_sample(cell, fx.centre[a] * g, fy.centre[b] * g, z, w * fx.fraction[a] * fy.fraction[b]);
        }
    }
    ++counters_.points_fused;
    ++counters_.points_spread;
}

template <typename Grid>
inline void TerrainMapper::fuse_point(Grid& grid, float x, float y, double z, float variance_m2)
{
    variance_m2 = std::max(variance_m2, static_cast<float>(config_.min_variance_m2));
    const float w = config_.statistics == StatisticsKind::classical ? 1.0f : 1.0f / variance_m2;
    if (config_.spread && variance_m2 > static_cast<float>(config_.grid_size_m * config_.grid_size_m)) {
        spread_point(grid, grid.nx(), grid.ny(), x, y, z, variance_m2, w);
        return;
    }
    float x_rel = 0.0f, y_rel = 0.0f;
    const int cell = grid.locate(x, y, x_rel, y_rel);
    if (cell < 0) {
        ++counters_.rejected_outside_map;
        return;
    }
    fuse_sample(grid.at(cell), x_rel, y_rel, z, w);
    ++counters_.points_fused;
}

template <typename Grid>
std::size_t TerrainMapper::fuse_into(Grid& grid, const PointBatch& batch)
{
    const uint64_t fused_before = counters_.points_fused;
    const std::size_t n = batch.count;
    if (history_.empty()) {
        counters_.rejected_no_pose += n;
        return 0;
    }
    // The batch's time span: the poses at its two ends bound every point's pose.
    float t_min = std::numeric_limits<float>::infinity(), t_max = -t_min;
    for (std::size_t k = 0; k < n; ++k) {
        const float t = batch.time_offset_s[k];
        const bool finite = t * 0.0f == 0.0f;  // branch-free, so that it vectorises
        const float lo = finite ? t : std::numeric_limits<float>::infinity();
        const float hi = finite ? t : -std::numeric_limits<float>::infinity();
        t_min = lo < t_min ? lo : t_min;
        t_max = hi > t_max ? hi : t_max;
    }
    const Frame frame = local_frame();
    Pose p0, p1;
    const bool fast = t_min <= t_max && t_max - t_min <= config_.max_interpolation_span_s &&
                      history_.at(batch.utime_us + std::llround(t_min * 1e6), p0) == PoseHistory::Lookup::ok &&
                      history_.at(batch.utime_us + std::llround(t_max * 1e6), p1) == PoseHistory::Lookup::ok;
    if (fast) {
        // Over a scan (13-27 ms) the transform changes by a small rotation: blending the two
        // end transforms linearly is within (d_angle^2)/8 of the slerp, < 0.1 mm at 30 m
        // for 1 rad/s, and exact at the ends. The eq. 19 orientation error blends likewise.
        const Affine a0 = body_to_local(p0, frame.origin_m, frame.yaw_rad);
        const Affine a1 = body_to_local(p1, frame.origin_m, frame.yaw_rad);
        float da[9], db[3];
        for (int i = 0; i < 9; ++i) da[i] = a1.a[i] - a0.a[i];
        for (int i = 0; i < 3; ++i) db[i] = a1.b[i] - a0.b[i];
        const float de0 = static_cast<float>(p0.orientation_error_rad2());
        const float dde = static_cast<float>(p1.orientation_error_rad2()) - de0;
        const float inv_span = t_max > t_min ? 1.0f / (t_max - t_min) : 0.0f;
        const float min_variance = static_cast<float>(config_.min_variance_m2);
        const float spread_above = config_.spread ? static_cast<float>(config_.grid_size_m * config_.grid_size_m)
                                                  : std::numeric_limits<float>::infinity();
        const bool classical = config_.statistics == StatisticsKind::classical;
        // Two passes over chunks of points: the first transforms and indexes them and
        // prefetches their cells, the second fuses. The map (1.4 MB at 150x150) does not
        // stay in L2, so overlapping the cache misses is what sets the throughput.
        constexpr std::size_t kChunk = 64;
        float lx[kChunk], ly[kChunk], lz[kChunk], s2[kChunk], w[kChunk], xr[kChunk], yr[kChunk];
        int ci[kChunk], cj[kChunk];
        uint8_t inside[kChunk];
        const float g = static_cast<float>(config_.grid_size_m);
        const float inv_g = 1.0f / g;
        const float y_min = static_cast<float>(grid.y_min_m());
        const float nx_f = static_cast<float>(grid.nx()), ny_f = static_cast<float>(grid.ny());
        const float nx_last = nx_f - 0.5f, ny_last = ny_f - 0.5f;
        uint8_t valid[kChunk];
        // Classical statistics fuse with unit weight: w = vw_scale / s2 + unit_weight.
        const float vw_scale = classical ? 0.0f : 1.0f;
        const float unit_weight = classical ? 1.0f : 0.0f;
        int cell[kChunk];
        float x_rel[kChunk], y_rel[kChunk], height[kChunk], weight[kChunk];
        uint64_t fused = 0, non_finite = 0, outside = 0;
        for (std::size_t base = 0; base < n; base += kChunk) {
            const std::size_t count = std::min(n - base, kChunk);
            const float* px = batch.x_m + base;
            const float* py = batch.y_m + base;
            const float* pz = batch.z_m + base;
            const float* pr = batch.range_m + base;
            const float* pv = batch.variance_m2 + base;
            const float* pt = batch.time_offset_s + base;
            // Pass 1, branch-free so that it vectorises: transform (the end transforms blended
            // at each point's time), eq. 19 variance, weight.
            for (std::size_t k = 0; k < count; ++k) {
                const float x = px[k], y = py[k], z = pz[k], r = pr[k], v = pv[k], t = pt[k];
                valid[k] = static_cast<uint8_t>(static_cast<uint8_t>(all_finite(x, y, z, r, v, t)) &
                                                static_cast<uint8_t>(v >= 0.0f));
                const float f = (t - t_min) * inv_span;
                lx[k] = (a0.a[0] + f * da[0]) * x + (a0.a[1] + f * da[1]) * y + (a0.a[2] + f * da[2]) * z +
                        (a0.b[0] + f * db[0]);
                ly[k] = (a0.a[3] + f * da[3]) * x + (a0.a[4] + f * da[4]) * y + (a0.a[5] + f * da[5]) * z +
                        (a0.b[1] + f * db[1]);
                lz[k] = (a0.a[6] + f * da[6]) * x + (a0.a[7] + f * da[7]) * y + (a0.a[8] + f * da[8]) * z +
                        (a0.b[2] + f * db[2]);
                const float raw = point_variance_m2(v, r, de0 + f * dde);
                const float var = raw > min_variance ? raw : min_variance;
                s2[k] = var;
                w[k] = vw_scale / var + unit_weight;
                // Eq. 5-7 (without the wrap, which pass 2 adds): the cell and the offset from its centre.
                const float fx = lx[k] * inv_g;
                const float fy = (ly[k] - y_min) * inv_g;
                inside[k] = static_cast<uint8_t>(static_cast<uint8_t>(fx >= 0.0f) & static_cast<uint8_t>(fx < nx_f) &
                                                 static_cast<uint8_t>(fy >= 0.0f) & static_cast<uint8_t>(fy < ny_f));
                // Clamped so that the conversion is defined for any value (NaN goes to 0).
                const float fx0 = fx > 0.0f ? fx : 0.0f;
                const float fy0 = fy > 0.0f ? fy : 0.0f;
                const float fxc = fx0 < nx_last ? fx0 : nx_last;
                const float fyc = fy0 < ny_last ? fy0 : ny_last;
                ci[k] = static_cast<int>(fxc);
                cj[k] = static_cast<int>(fyc);
                xr[k] = lx[k] - (static_cast<float>(ci[k]) + 0.5f) * g;
                yr[k] = ly[k] - y_min - (static_cast<float>(cj[k]) + 0.5f) * g;
            }
            // Pass 2: index, prefetch the cell (the map does not stay in L2, so overlapping
            // the cache misses is what sets the throughput), or spread.
            std::size_t m = 0;
            for (std::size_t k = 0; k < count; ++k) {
                if (!valid[k]) {
                    ++non_finite;
                    continue;
                }
                if (s2[k] > spread_above) {
                    spread_point(grid, grid.nx(), grid.ny(), lx[k], ly[k], lz[k], s2[k], w[k]);
                    continue;
                }
                if (!inside[k]) {
                    ++outside;
                    continue;
                }
                const int c = grid.physical(ci[k], cj[k]);
                x_rel[m] = xr[k];
                y_rel[m] = yr[k];
                __builtin_prefetch(&grid.at(c), 1);
                cell[m] = c;
                height[m] = lz[k];
                weight[m] = w[k];
                ++m;
            }
            // Pass 3: the ten sums.
            for (std::size_t q = 0; q < m; ++q) fuse_sample(grid.at(cell[q]), x_rel[q], y_rel[q], height[q], weight[q]);
            fused += m;
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
            const auto found = history_.at(batch.utime_us + std::llround(static_cast<double>(t) * 1e6), p);
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
            fuse_point(grid, lx, ly, lz, point_variance_m2(v, r, static_cast<float>(p.orientation_error_rad2())));
        }
    }
    return static_cast<std::size_t>(counters_.points_fused - fused_before);
}

std::size_t TerrainMapper::fuse(const PointBatch& batch)
{
    if (ego_) return fuse_into(*ego_, batch);
    return fuse_into(*world_, batch);
}

void TerrainMapper::snapshot(MapSnapshot& out) const
{
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
    out.count.assign(cells, 0);
    const double y_min = -0.5 * ny * g;
    auto put = [&](std::size_t k, const CellSums& c) {
        if (c.n == 0) return;
        const CellStatistics s = cell_statistics(c, config_.statistics);
        out.mean_z_m[k] = static_cast<float>(s.mean_z_m);
        out.variance_z_m2[k] = static_cast<float>(s.variance_z_m2);
        out.count[k] = static_cast<int32_t>(std::min<uint32_t>(c.n, 0x7fffffff));
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
        const Eigen::Vector2d body = rot2(-anchor_yaw_rad_) * (pose.position_m.head<2>() - anchor_m_);
        const Eigen::Vector2d ref = rot2(-anchor_yaw_rad_) * (reference_world(pose) - anchor_m_);
        out.origin_x_m = -body.x();
        out.origin_y_m = y_min - body.y();
        out.wrap_index = ego_->wrap_index();
        out.x_curr_m = ref.x();
        out.residual_yaw_rad = wrap_angle_rad(yaw - anchor_yaw_rad_);
        for (int i = 0; i < nx; ++i)
            for (int j = 0; j < ny; ++j) put(static_cast<std::size_t>(i * ny + j), ego_->at(i, j));
        return;
    }
    // World-aligned: resample into the vehicle's heading at the reference point (nearest cell).
    const Eigen::Vector2d ref = reference_world(pose);
    const Eigen::Matrix2d turn = rot2(yaw);
    out.origin_x_m = config_.reference_x_m;
    out.origin_y_m = config_.reference_y_m + y_min;
    out.wrap_index = 0;
    out.x_curr_m = 0.0;
    out.residual_yaw_rad = 0.0;
    for (int i = 0; i < nx; ++i) {
        for (int j = 0; j < ny; ++j) {
            const Eigen::Vector2d local((i + 0.5) * g, y_min + (j + 0.5) * g);
            const CellSums* c = world_->cell_at(ref + turn * local);
            if (c) put(static_cast<std::size_t>(i * ny + j), *c);
        }
    }
}

CellStatistics TerrainMapper::statistics_at_body(double x_m, double y_m) const
{
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    if (history_.empty()) return {nan, nan};
    const Pose& pose = history_.newest();
    const Eigen::Vector2d world = pose.position_m.head<2>() + rot2(pose.yaw_rad()) * Eigen::Vector2d(x_m, y_m);
    if (ego_) {
        const Eigen::Vector2d local = rot2(-anchor_yaw_rad_) * (world - anchor_m_);
        float xr = 0, yr = 0;
        const int cell = ego_->locate(static_cast<float>(local.x()), static_cast<float>(local.y()), xr, yr);
        if (cell < 0) return {nan, nan};
        return cell_statistics(ego_->at(cell), config_.statistics);
    }
    const CellSums* c = world_->cell_at(world);
    if (!c) return {nan, nan};
    return cell_statistics(*c, config_.statistics);
}

CellSums TerrainMapper::total() const
{
    CellSums sum;
    if (ego_) {
        for (int i = 0; i < ego_->nx(); ++i)
            for (int j = 0; j < ego_->ny(); ++j) add_sums(sum, ego_->at(i, j));
    } else {
        const int n = world_->size();
        for (int k = 0; k < n * n; ++k) add_sums(sum, world_->at(k));
    }
    return sum;
}

}  // namespace ugv::terrain
