#include "traverse_score.hpp"

#include <lcm/lcm-cpp.hpp>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <vector>

#include <ugv/candidate_arcs_t.hpp>
#include <ugv/sim_truth_t.hpp>
#include <ugv/terrain_map_t.hpp>
#include <ugv/traversability_map_t.hpp>

#include "ugv/bus/typed.hpp"
#include "ugv/terrain/evaluation.hpp"
#include "ugv/traverse/candidate_arcs.hpp"

namespace ugv::eval {
namespace {

constexpr int kMaxCells = 4'000'000;  // as lib/traverse's check_grid
// Heights are float32 (the truth's and the map's samples): within their rounding of the
// obstacle's threshold height, a sample counts as one of it. Not the laser's noise.
constexpr double kSampleTolerance = 1e-5;
// How far a column may lie outside its cell's samples and still count as seen: the laser's
// noise and the pose's error at range, with the rough ground's 2 cm between a cell's columns.
constexpr double kSeenHeightTolerance = 0.05;

bool finite_pose(const pose_t& p)
{
    for (double v : p.position)
        if (!std::isfinite(v)) return false;
    double n2 = 0.0;
    for (double v : p.orientation) {
        if (!std::isfinite(v)) return false;
        n2 += v * v;
    }
    return n2 > 0.25;
}

terrain::Pose to_pose(const pose_t& p)
{
    terrain::Pose out;
    out.utime_us = p.utime;
    out.position_m = {p.position[0], p.position[1], p.position[2]};
    out.orientation = Eigen::Quaterniond(p.orientation[0], p.orientation[1], p.orientation[2], p.orientation[3]).normalized();
    return out;
}

// Why a traversability map cannot be scored (empty: it can).
std::string check_map(const traversability_map_t& m)
{
    if (!finite_pose(m.pose)) return "pose not finite";
    if (!(std::isfinite(m.resolution) && m.resolution > 0.0f)) return "resolution not positive";
    if (m.nx <= 0 || m.ny <= 0 || static_cast<int64_t>(m.nx) * m.ny > kMaxCells ||
        static_cast<int64_t>(m.nx) * m.ny != m.ncells)
        return "sizes disagree";
    if (!std::isfinite(m.origin_x) || !std::isfinite(m.origin_y) || !std::isfinite(m.residual_yaw))
        return "origin or residual yaw not finite";
    for (int8_t c : m.cell_class)
        if (c < traversability_map_t::CLASS_UNKNOWN || c > traversability_map_t::CLASS_NEGATIVE_OBSTACLE)
            return "cell class out of range";
    return {};
}

std::string check_arcs(const candidate_arcs_t& a)
{
    if (!finite_pose(a.pose)) return "pose not finite";
    if (!(std::isfinite(a.length_m) && a.length_m > 0.0f && a.length_m < 1000.0f)) return "length not positive";
    if (!(std::isfinite(a.swept_width_m) && a.swept_width_m > 0.0f && a.swept_width_m < 100.0f))
        return "swept width not positive";
    for (float k : a.curvature)
        if (!std::isfinite(k)) return "curvature not finite";
    return {};
}

// One traversability map placed in the world with the terrain library's transform
// (terrain::cell_centre_world); its inverse is taken from the same transform's axes.
class PlacedClasses
{
public:
    explicit PlacedClasses(const traversability_map_t& m) : cls_(m.cell_class)
    {
        snap_.pose = to_pose(m.pose);
        snap_.resolution_m = m.resolution;
        snap_.nx = m.nx;
        snap_.ny = m.ny;
        snap_.origin_x_m = m.origin_x;
        snap_.origin_y_m = m.origin_y;
        snap_.residual_yaw_rad = m.residual_yaw;
        const Eigen::Vector2d c00 = terrain::cell_centre_world(snap_, 0, 0);
        axis_i_ = (terrain::cell_centre_world(snap_, 1, 0) - c00) / snap_.resolution_m;
        axis_j_ = (terrain::cell_centre_world(snap_, 0, 1) - c00) / snap_.resolution_m;
        corner_ = c00 - 0.5 * snap_.resolution_m * (axis_i_ + axis_j_);
        const double yaw = snap_.pose.yaw_rad();
        cos_yaw_ = std::cos(yaw);
        sin_yaw_ = std::sin(yaw);
    }
    int nx() const { return snap_.nx; }
    int ny() const { return snap_.ny; }
    double resolution() const { return snap_.resolution_m; }
    int8_t cls(int i, int j) const { return cls_[static_cast<std::size_t>(i * snap_.ny + j)]; }
    Eigen::Vector2d centre_world(int i, int j) const { return terrain::cell_centre_world(snap_, i, j); }
    const Eigen::Vector2d& axis_i() const { return axis_i_; }
    const Eigen::Vector2d& axis_j() const { return axis_j_; }
    // The cell holding world point w; false outside the map.
    bool cell_at(const Eigen::Vector2d& w, int& i, int& j) const
    {
        const Eigen::Vector2d d = w - corner_;
        const double u = std::floor(d.dot(axis_i_) / snap_.resolution_m), v = std::floor(d.dot(axis_j_) / snap_.resolution_m);
        if (!(u >= 0 && u < snap_.nx && v >= 0 && v < snap_.ny)) return false;
        i = static_cast<int>(u);
        j = static_cast<int>(v);
        return true;
    }
    // The index (i * ny + j) of the known cell holding world point w; -1 outside the map or
    // where the cell is unknown.
    std::ptrdiff_t known_cell(const Eigen::Vector2d& w) const
    {
        int i, j;
        if (!cell_at(w, i, j) || cls(i, j) == traversability_map_t::CLASS_UNKNOWN) return -1;
        return static_cast<std::ptrdiff_t>(i) * snap_.ny + j;
    }
    // World -> body frame (x forward, y left) with the pose's position and yaw.
    Eigen::Vector2d body(const Eigen::Vector2d& w) const
    {
        const Eigen::Vector2d d = w - snap_.pose.position_m.head<2>();
        return {cos_yaw_ * d.x() + sin_yaw_ * d.y(), -sin_yaw_ * d.x() + cos_yaw_ * d.y()};
    }
    Eigen::Vector2d position() const { return snap_.pose.position_m.head<2>(); }

private:
    terrain::MapSnapshot snap_;
    std::vector<int8_t> cls_;
    Eigen::Vector2d axis_i_, axis_j_, corner_;
    double cos_yaw_ = 1.0, sin_yaw_ = 0.0;
};

bool is_obstacle(int8_t c)
{
    return c == traversability_map_t::CLASS_OBSTACLE || c == traversability_map_t::CLASS_NEGATIVE_OBSTACLE;
}
bool is_obstacle(TruthClass c) { return c == TruthClass::obstacle || c == TruthClass::negative; }

// The truth of a map cell from the columns under a grid of points at the truth's resolution
// over it: obstacle if any is, else negative if any is, else traversable (none: no column).
// For telling whether the laser sampled the obstacle (an obstacle is a height against a
// local ground, so both must have been sampled): a step obstacle needs a sample in the cell
// at `above` or higher and one within the ground radius at `ground_below` or lower (the lowest
// of its step columns' local ground + max_step, and that ground + max_step / 2, the ground
// taken over the columns the map knows: a column that is no step over those is not counted); a slope
// obstacle needs only a sample in the cell (`above` = -inf); a negative cell needs a sample
// in it at `below` or lower (the highest of its columns' ground - max_drop) and one around
// at `ground_above` or higher (that ground - max_drop / 2).
struct CellTruth
{
    TruthClass cls = TruthClass::none;
    double above = std::numeric_limits<double>::infinity();
    double ground_below = -std::numeric_limits<double>::infinity();
    double below = -std::numeric_limits<double>::infinity();
    double ground_above = std::numeric_limits<double>::infinity();
};

CellTruth cell_truth(const TruthTerrain& truth, const SeenGround& seen_ground, const PlacedClasses& map, int i, int j)
{
    const double res = map.resolution();
    const simworld::HeightField& f = truth.field();
    const TruthRules& r = truth.rules();
    const int n = std::max(1, static_cast<int>(std::ceil(res / f.resolution_m - 1e-6)));
    const Eigen::Vector2d c = map.centre_world(i, j);
    CellTruth out;
    for (int a = 0; a < n; ++a) {
        for (int b = 0; b < n; ++b) {
            const Eigen::Vector2d p = c + map.axis_i() * (res * ((a + 0.5) / n - 0.5)) +
                                      map.axis_j() * (res * ((b + 0.5) / n - 0.5));
            int ci, cj;
            if (!truth.column_of(p.x(), p.y(), ci, cj)) continue;
            const TruthClass t = truth.column_class(ci, cj);
            const double ground = truth.ground_height(ci, cj);
            if (t == TruthClass::obstacle) {
                out.cls = t;
                if (f.at(ci, cj) - ground >= r.max_step_m - kSampleTolerance) {
                    // Sampled only if it stands max_step above the ground the laser has seen
                    // around it: behind a ramp's high edge the lower ground lies in the
                    // edge's shadow, and the ramp's top is no step over what was seen.
                    const double seen = seen_ground.ground(ci, cj);
                    if (f.at(ci, cj) - seen >= r.max_step_m - kSampleTolerance) {
                        out.above = std::min(out.above, seen + r.max_step_m);
                        out.ground_below = std::max(out.ground_below, seen + 0.5 * r.max_step_m);
                    }
                } else {
                    out.above = -std::numeric_limits<double>::infinity();
                }
            } else if (t == TruthClass::negative && out.cls != TruthClass::obstacle) {
                out.cls = t;
                out.below = std::max(out.below, ground - r.max_drop_m);
                out.ground_above = std::min(out.ground_above, ground - 0.5 * r.max_drop_m);
            } else if (t == TruthClass::traversable && out.cls == TruthClass::none) {
                out.cls = t;
            }
        }
    }
    return out;
}

// The highest and lowest samples of one terrain map's cells (the map a traversability map
// was computed from), for telling an obstacle the laser sampled from one it saw only the
// foot of.
struct SampledExtremes
{
    int nx = 0, ny = 0;
    float origin_x = 0, origin_y = 0;
    std::vector<float> max_z, min_z;
};

std::string number(double v)
{
    char buf[32] = "null";
    if (std::isfinite(v)) std::snprintf(buf, sizeof buf, "%.3f", v);
    return buf;
}

// A cell the map got wrong, for --misses: where it is and what each side says.
void print_miss(std::FILE* out, const traversability_map_t& m, const PlacedClasses& map, int i, int j, const char* what,
                TruthClass truth, const SampledExtremes* terrain, double sample_threshold_m, bool sampled)
{
    if (out == nullptr) return;
    const Eigen::Vector2d w = map.centre_world(i, j), b = map.body(w);
    static const char* const names[] = {"none", "traversable", "obstacle", "negative"};
    const std::size_t k = static_cast<std::size_t>(i) * static_cast<std::size_t>(m.ny) + static_cast<std::size_t>(j);
    auto layer = [&](const std::vector<float>& v) {
        return number(v.size() == m.cell_class.size() ? double(v[k]) : std::numeric_limits<double>::quiet_NaN());
    };
    std::fprintf(out,
                 "{\"map_seq\": %lld, \"what\": \"%s\", \"i\": %d, \"j\": %d, \"x\": %.2f, \"y\": %.2f, "
                 "\"body_x\": %.2f, \"body_y\": %.2f, \"truth\": \"%s\", \"map_class\": %d, \"step_m\": %s, "
                 "\"drop_m\": %s, \"slope_deg\": %s, \"max_z\": %s, \"min_z\": %s, \"sample_threshold_z\": %s, "
                 "\"sampled\": %s}\n",
                 static_cast<long long>(m.map_seq), what, i, j, w.x(), w.y(), b.x(), b.y(), names[static_cast<int>(truth)],
                 map.cls(i, j), layer(m.step_m).c_str(), layer(m.drop_m).c_str(), layer(m.slope_deg).c_str(),
                 terrain != nullptr ? layer(terrain->max_z).c_str() : "null",
                 terrain != nullptr ? layer(terrain->min_z).c_str() : "null", number(sample_threshold_m).c_str(),
                 sampled ? "true" : "false");
}

// Whether the terrain map holds samples of obstacle cell (i, j) and of the ground it stands
// above (lies below) within `radius` cells (CellTruth).
bool sampled_obstacle(const SampledExtremes& t, const CellTruth& c, int i, int j, int radius, int slope_radius,
                      double slope_span_m)
{
    const std::size_t k = static_cast<std::size_t>(i) * static_cast<std::size_t>(t.ny) + static_cast<std::size_t>(j);
    const bool positive = c.cls == TruthClass::obstacle;
    if (positive ? !(t.max_z[k] >= c.above - kSampleTolerance) : !(t.min_z[k] <= c.below + kSampleTolerance)) return false;
    if (positive && c.above == -std::numeric_limits<double>::infinity()) {
        float high = -std::numeric_limits<float>::infinity(), low = std::numeric_limits<float>::infinity();
        for (int a = std::max(0, i - slope_radius); a <= std::min(t.nx - 1, i + slope_radius); ++a) {
            for (int b = std::max(0, j - slope_radius); b <= std::min(t.ny - 1, j + slope_radius); ++b) {
                const std::size_t n = static_cast<std::size_t>(a) * static_cast<std::size_t>(t.ny) + static_cast<std::size_t>(b);
                if (t.max_z[n] > high) high = t.max_z[n];
                if (t.min_z[n] < low) low = t.min_z[n];
            }
        }
        return high - low >= slope_span_m;
    }
    for (int a = std::max(0, i - radius); a <= std::min(t.nx - 1, i + radius); ++a) {
        for (int b = std::max(0, j - radius); b <= std::min(t.ny - 1, j + radius); ++b) {
            if ((a - i) * (a - i) + (b - j) * (b - j) > radius * radius) continue;
            const std::size_t n = static_cast<std::size_t>(a) * static_cast<std::size_t>(t.ny) + static_cast<std::size_t>(b);
            if (positive ? t.min_z[n] <= c.ground_below : t.max_z[n] >= c.ground_above) return true;
        }
    }
    return false;
}

// `sampled_cells` (nx * ny) is set where a known truth-obstacle cell at any range was sampled.
void score_cells(const TruthTerrain& truth, const traversability_map_t& m, const PlacedClasses& map,
                 const SampledExtremes* terrain, double range_m, std::FILE* misses, TraverseScore& s,
                 std::vector<char>& sampled_cells)
{
    const int nx = map.nx(), ny = map.ny();
    std::vector<TruthClass> t(static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny));
    std::vector<CellTruth> cells(t.size());
    const simworld::HeightField& f = truth.field();
    // Seen ground: a column in a known cell, at a height the cell's samples reach. A cell known
    // for a face's samples has not seen the ground at the face's foot, nor the floor beside it.
    auto seen = [&](int a, int b) {
        const std::ptrdiff_t k = map.known_cell({f.cell_x(a), f.cell_y(b)});
        if (k < 0) return false;
        if (terrain == nullptr) return true;
        const double z = f.at(a, b);
        const auto u = static_cast<std::size_t>(k);
        return z >= terrain->min_z[u] - kSeenHeightTolerance && z <= terrain->max_z[u] + kSeenHeightTolerance;
    };
    const SeenGround seen_ground(truth, seen);
    for (int i = 0; i < nx; ++i) {
        for (int j = 0; j < ny; ++j) {
            const std::size_t k = static_cast<std::size_t>(i * ny + j);
            cells[k] = cell_truth(truth, seen_ground, map, i, j);
            t[k] = cells[k].cls;
        }
    }
    // The one-cell tolerance: the 8-neighbourhood and the cell itself.
    auto near = [&](int i, int j, auto&& pred) {
        for (int a = std::max(0, i - 1); a <= std::min(nx - 1, i + 1); ++a)
            for (int b = std::max(0, j - 1); b <= std::min(ny - 1, j + 1); ++b)
                if (pred(a, b)) return true;
        return false;
    };
    auto map_obstacle = [&](int a, int b) { return is_obstacle(map.cls(a, b)); };
    const TruthRules& rules = truth.rules();
    const int ground_cells = static_cast<int>(std::floor(rules.ground_radius_m / map.resolution() + 1e-6));
    const int slope_cells = static_cast<int>(std::ceil(rules.slope_radius_m / map.resolution() - 1e-6));
    const double slope_span_m = std::tan(rules.max_slope_deg * M_PI / 180.0) * rules.slope_radius_m;
    auto truth_obstacle = [&](int a, int b) { return is_obstacle(t[static_cast<std::size_t>(a * ny + b)]); };
    sampled_cells.assign(t.size(), 0);
    for (int i = 0; i < nx; ++i) {
        for (int j = 0; j < ny; ++j) {
            const std::size_t k = static_cast<std::size_t>(i * ny + j);
            const TruthClass tc = t[k];
            if (tc == TruthClass::none) continue;
            const int8_t mc = map.cls(i, j);
            const bool known = mc != traversability_map_t::CLASS_UNKNOWN;
            const bool sampled = known && is_obstacle(tc) && terrain != nullptr &&
                                 sampled_obstacle(*terrain, cells[k], i, j, ground_cells, slope_cells, slope_span_m);
            sampled_cells[k] = sampled ? 1 : 0;
            const double ahead = map.body(map.centre_world(i, j)).x();
            if (!(ahead >= 0.0 && ahead <= range_m)) continue;
            if (tc == TruthClass::traversable) {
                if (!known) continue;
                ++s.traversable_known;
                if (mc == traversability_map_t::CLASS_TRAVERSABLE || near(i, j, truth_obstacle)) continue;
                if (mc == traversability_map_t::CLASS_OBSTACLE) ++s.false_obstacles;
                else ++s.false_negative_obstacles;
                print_miss(misses, m, map, i, j, "false", tc, terrain, std::numeric_limits<double>::quiet_NaN(), false);
                continue;
            }
            const bool positive = tc == TruthClass::obstacle;
            ++(positive ? s.obstacle_cells : s.negative_cells);
            if (!known) continue;
            ++(positive ? s.obstacle_seen : s.negative_seen);
            const bool detected = near(i, j, map_obstacle);
            if (detected) ++(positive ? s.obstacle_detected : s.negative_detected);
            const double threshold = positive ? cells[k].above : cells[k].below;
            if (!detected) print_miss(misses, m, map, i, j, "missed", tc, terrain, threshold, sampled);
            if (!sampled) continue;
            ++s.sampled;
            s.sampled_detected += detected ? 1 : 0;
        }
    }
}

struct TruthColumn
{
    Eigen::Vector2d body_m;
    bool seen;     // its map cell is known
    bool sampled;  // its map cell is a sampled obstacle cell
};

// `sampled_cells` from score_cells; null when the map came without its terrain map.
void score_arcs(const TruthTerrain& truth, const PlacedClasses& map, const candidate_arcs_t& arcs, double rear_x_m,
                double front_x_m, const std::vector<char>* sampled_cells, TraverseScore& s)
{
    traverse::Footprint fp;
    fp.rear_x_m = rear_x_m;
    fp.front_x_m = front_x_m;
    fp.width_m = arcs.swept_width_m;  // the margin is in it
    const double length = arcs.length_m;
    const double half_width = 0.5 * fp.width_m, tip = std::max(std::abs(rear_x_m), std::abs(front_x_m));
    const double corner = std::hypot(tip, half_width);
    const double reach = length + corner;
    // The truth's obstacle columns within reach of the body origin, in the body frame of the
    // arcs' pose (the map's pose: the same map_seq).
    const simworld::HeightField& f = truth.field();
    const Eigen::Vector2d origin(arcs.pose.position[0], arcs.pose.position[1]);
    std::vector<TruthColumn> columns;
    int i0, j0, i1, j1;
    const bool lo = truth.column_of(std::max(origin.x() - reach, f.origin_x_m), std::max(origin.y() - reach, f.origin_y_m), i0, j0);
    const bool hi = truth.column_of(std::min(origin.x() + reach, f.origin_x_m + (f.nx - 0.5) * f.resolution_m),
                                    std::min(origin.y() + reach, f.origin_y_m + (f.ny - 0.5) * f.resolution_m), i1, j1);
    const double yaw = to_pose(arcs.pose).yaw_rad();
    const double cy = std::cos(yaw), sy = std::sin(yaw);
    if (lo && hi) {
        for (int i = i0; i <= i1; ++i) {
            for (int j = j0; j <= j1; ++j) {
                if (!is_obstacle(truth.column_class(i, j))) continue;
                const Eigen::Vector2d w(f.cell_x(i), f.cell_y(j));
                const Eigen::Vector2d d = w - origin;
                const Eigen::Vector2d b(cy * d.x() + sy * d.y(), -sy * d.x() + cy * d.y());
                if (b.norm() > reach) continue;
                const std::ptrdiff_t cell = map.known_cell(w);
                const bool sampled = cell >= 0 && sampled_cells != nullptr && (*sampled_cells)[static_cast<std::size_t>(cell)] != 0;
                columns.push_back({b, cell >= 0, sampled});
            }
        }
    }
    for (int k = 0; k < arcs.narcs; ++k) {
        const double curv = arcs.curvature[static_cast<std::size_t>(k)];
        bool blocked_sampled = false, blocked_seen = false, blocked_all = false;
        for (const TruthColumn& c : columns) {
            // Only a column that could still change one of the three verdicts.
            if (blocked_all && (blocked_seen || !c.seen) && (blocked_sampled || !c.sampled)) continue;
            // Outside the band the footprint can sweep (a strip, or an annulus about the turn
            // centre from the inner side's radius to the outer front corner's): never covered.
            if (std::abs(curv) < 1e-9) {
                if (std::abs(c.body_m.y()) > half_width || c.body_m.x() < rear_x_m || c.body_m.x() > length + front_x_m)
                    continue;
            } else {
                const double radius = 1.0 / std::abs(curv);
                const double from_centre = (c.body_m - Eigen::Vector2d(0.0, 1.0 / curv)).norm();
                if (from_centre < radius - half_width - 1e-6 || from_centre > std::hypot(radius + half_width, tip) + 1e-6)
                    continue;
            }
            const double at = traverse::first_cover_s(curv, fp, 0.0, length, c.body_m, f.resolution_m);
            if (std::isnan(at)) continue;
            blocked_all = true;
            if (c.seen) blocked_seen = true;
            if (c.sampled) blocked_sampled = true;
            if (blocked_seen && (blocked_sampled || sampled_cells == nullptr)) break;
        }
        const bool said = arcs.blocked[static_cast<std::size_t>(k)] != 0;
        ++s.arcs;
        s.arcs_blocked += said ? 1 : 0;
        s.arcs_truth_blocked += blocked_seen ? 1 : 0;
        s.arcs_agree += said == blocked_seen ? 1 : 0;
        s.arcs_truth_blocked_unrestricted += blocked_all ? 1 : 0;
        s.arcs_agree_unrestricted += said == blocked_all ? 1 : 0;
        if (sampled_cells != nullptr) {
            ++s.arcs_with_terrain;
            s.arcs_truth_blocked_sampled += blocked_sampled ? 1 : 0;
            s.arcs_agree_sampled += said == blocked_sampled ? 1 : 0;
        }
    }
}

std::string ratio(long num, long den)
{
    if (den <= 0) return "null";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.5f", static_cast<double>(num) / static_cast<double>(den));
    return buf;
}

}  // namespace

void TraverseScore::add(const TraverseScore& o)
{
    obstacle_cells += o.obstacle_cells, obstacle_seen += o.obstacle_seen, obstacle_detected += o.obstacle_detected;
    negative_cells += o.negative_cells, negative_seen += o.negative_seen, negative_detected += o.negative_detected;
    traversable_known += o.traversable_known, false_obstacles += o.false_obstacles;
    false_negative_obstacles += o.false_negative_obstacles;
    arcs += o.arcs, arcs_blocked += o.arcs_blocked;
    arcs_truth_blocked += o.arcs_truth_blocked, arcs_agree += o.arcs_agree;
    arcs_truth_blocked_unrestricted += o.arcs_truth_blocked_unrestricted;
    arcs_agree_unrestricted += o.arcs_agree_unrestricted;
    arcs_with_terrain += o.arcs_with_terrain, arcs_truth_blocked_sampled += o.arcs_truth_blocked_sampled;
    arcs_agree_sampled += o.arcs_agree_sampled;
    sampled += o.sampled, sampled_detected += o.sampled_detected;
}

std::string TraverseScore::json() const
{
    std::ostringstream o;
    o << "\"obstacle_cells\": " << obstacle_cells << ", \"obstacle_seen\": " << obstacle_seen
      << ", \"obstacle_detected\": " << obstacle_detected
      << ", \"obstacle_recall\": " << ratio(obstacle_detected, obstacle_seen) << ", \"negative_cells\": " << negative_cells
      << ", \"negative_seen\": " << negative_seen << ", \"negative_detected\": " << negative_detected
      << ", \"negative_recall\": " << ratio(negative_detected, negative_seen)
      << ", \"recall\": " << ratio(obstacle_detected + negative_detected, obstacle_seen + negative_seen)
      << ", \"sampled\": " << sampled << ", \"sampled_detected\": " << sampled_detected
      << ", \"sampled_recall\": " << ratio(sampled_detected, sampled)
      << ", \"traversable_known\": " << traversable_known << ", \"false_obstacles\": " << false_obstacles
      << ", \"false_negative_obstacles\": " << false_negative_obstacles
      << ", \"false_obstacle_rate\": " << ratio(false_obstacles + false_negative_obstacles, traversable_known)
      << ", \"arcs\": " << arcs << ", \"arcs_blocked\": " << arcs_blocked
      << ", \"arcs_truth_blocked\": " << arcs_truth_blocked << ", \"arcs_agree\": " << arcs_agree
      << ", \"arc_agreement\": " << ratio(arcs_agree, arcs)
      << ", \"arcs_truth_blocked_unrestricted\": " << arcs_truth_blocked_unrestricted
      << ", \"arcs_agree_unrestricted\": " << arcs_agree_unrestricted
      << ", \"arc_agreement_unrestricted\": " << ratio(arcs_agree_unrestricted, arcs)
      << ", \"arcs_with_terrain\": " << arcs_with_terrain
      << ", \"arcs_truth_blocked_sampled\": " << arcs_truth_blocked_sampled
      << ", \"arcs_agree_sampled\": " << arcs_agree_sampled
      << ", \"arc_agreement_sampled\": " << ratio(arcs_agree_sampled, arcs_with_terrain);
    return o.str();
}

TraverseScoreCommand::TraverseScoreCommand(CLI::App& app)
{
    const traverse::Footprint fp;
    rear_x_m_ = fp.rear_x_m;
    front_x_m_ = fp.front_x_m;
    sub_ = app.add_subcommand("traverse", "the traversability maps and arcs of a log against a truth height field");
    sub_->add_option("log", log_, "LCM log with traversability_map_t (and candidate_arcs_t)")->required()->check(CLI::ExistingFile);
    sub_->add_option("--truth", truth_, "truth height field (ugv-sim world's run/truth.hf)")->required()->check(CLI::ExistingFile);
    sub_->add_option("--channel", channel_, "channel of the traversability maps");
    sub_->add_option("--arcs-channel", arcs_channel_, "channel of the candidate arcs");
    sub_->add_option("--terrain-channel", terrain_channel_,
                     "channel of the terrain maps the traversability maps were computed from (for sampled_recall)");
    sub_->add_option("--range-m", range_m_, "score the cells this far ahead of the vehicle (body x from 0)")
        ->check(CLI::Range(0.0, 1000.0));
    sub_->add_option("--rear-x-m", rear_x_m_, "the footprint's rear (body x, m) for judging arcs on the truth")
        ->check(CLI::Range(-20.0, 0.0));
    sub_->add_option("--front-x-m", front_x_m_, "the footprint's front (body x, m)")->check(CLI::Range(0.0, 20.0));
    sub_->add_option("--max-step-m", rules_.max_step_m, "truth: a column this high above the local ground is an obstacle")
        ->check(CLI::Range(0.01, 10.0));
    sub_->add_option("--max-drop-m", rules_.max_drop_m, "truth: a column this low below the local ground is a negative obstacle")
        ->check(CLI::Range(0.01, 10.0));
    sub_->add_option("--ground-radius-m", rules_.ground_radius_m,
                     "truth: the local ground is the detrended median within this (m)")
        ->check(CLI::Range(0.05, 20.0));
    sub_->add_option("--max-slope-deg", rules_.max_slope_deg, "truth: a steeper plane around a column is an obstacle")
        ->check(CLI::Range(1.0, 89.0));
    sub_->add_option("--slope-radius-m", rules_.slope_radius_m, "truth: the plane is fitted over this radius (m)")
        ->check(CLI::Range(0.01, 5.0));
    sub_->add_option("--misses", misses_,
                     "write each missed truth obstacle and each false obstacle (cell, world and body position, both "
                     "classes, the map's step, drop, slope) to this file, one JSON line each");
    sub_->add_option("--pose", pose_,
                     "where the maps are placed in the world: the simulator's true pose at the map's time (truth), "
                     "the map's own (estimate), or truth when the log has SIM_TRUTH (auto)")
        ->check(CLI::IsMember({"auto", "truth", "estimate"}));
    auto* all = sub_->add_flag("--all", all_, "a line for every map (the default)");
    sub_->add_flag("--last", last_, "a line for the last map only")->excludes(all);
}

int TraverseScoreCommand::run() const
{
    std::shared_ptr<simworld::HeightField> field;
    {
        std::ifstream in(truth_, std::ios::binary);
        std::stringstream bytes;
        bytes << in.rdbuf();
        try {
            field = std::make_shared<simworld::HeightField>(simworld::decode_height_field(bytes.str()));
        } catch (const std::invalid_argument& e) {
            std::fprintf(stderr, "ugv-eval: %s: %s\n", truth_.c_str(), e.what());
            return 2;
        }
    }
    const TruthTerrain truth(field, rules_);
    lcm::LogFile log(log_, "r");
    if (!log.good()) {
        std::fprintf(stderr, "ugv-eval: %s: not an LCM log\n", log_.c_str());
        return 2;
    }
    // Maps in log order, the arcs by the terrain map they judged (the last of each map_seq).
    std::vector<traversability_map_t> maps;
    std::map<int64_t, candidate_arcs_t> arcs;
    long malformed = 0, invalid_maps = 0, invalid_arcs = 0;
    std::vector<sim_truth_t> truth_poses;  // SIM_TRUTH in log order
    std::map<int64_t, SampledExtremes> terrain;  // by the terrain map's seq
    while (const lcm::LogEvent* ev = log.readNextEvent()) {
        const auto size = static_cast<std::size_t>(ev->datalen);
        if (ev->channel == "SIM_TRUTH" && pose_ != "estimate") {
            sim_truth_t t;
            if (bus::decode_checked(ev->data, size, t) && (truth_poses.empty() || t.utime > truth_poses.back().utime))
                truth_poses.push_back(std::move(t));
            continue;
        }
        if (ev->channel == terrain_channel_) {
            terrain_map_t t;
            if (!bus::decode_checked(ev->data, size, t)) {
                ++malformed;
            } else if (t.nx > 0 && t.ny > 0 && static_cast<int64_t>(t.nx) * t.ny == t.ncells &&
                       t.max_z.size() == static_cast<std::size_t>(t.ncells) && t.min_z.size() == t.max_z.size()) {
                terrain[t.seq] = {t.nx, t.ny, t.origin_x, t.origin_y, std::move(t.max_z), std::move(t.min_z)};
            }
            continue;
        }
        if (ev->channel == channel_) {
            traversability_map_t m;
            if (!bus::decode_checked(ev->data, size, m)) ++malformed;
            else if (const std::string why = check_map(m); !why.empty()) {
                ++invalid_maps;
                std::fprintf(stderr, "ugv-eval: %s: map seq %lld: %s (skipped)\n", channel_.c_str(),
                             static_cast<long long>(m.seq), why.c_str());
            } else {
                if (last_) maps.clear();
                maps.push_back(std::move(m));
            }
        } else if (ev->channel == arcs_channel_) {
            candidate_arcs_t a;
            if (!bus::decode_checked(ev->data, size, a)) ++malformed;
            else if (const std::string why = check_arcs(a); !why.empty()) {
                ++invalid_arcs;
                std::fprintf(stderr, "ugv-eval: %s: arcs of map seq %lld: %s (skipped)\n", arcs_channel_.c_str(),
                             static_cast<long long>(a.map_seq), why.c_str());
            } else {
                arcs[a.map_seq] = std::move(a);
            }
        }
    }
    if (malformed > 0)
        std::fprintf(stderr, "ugv-eval: %ld message(s) on %s or %s in %s could not be decoded (skipped)\n", malformed,
                     channel_.c_str(), arcs_channel_.c_str(), log_.c_str());
    std::unique_ptr<std::FILE, int (*)(std::FILE*)> misses(nullptr, &std::fclose);
    if (!misses_.empty()) {
        misses.reset(std::fopen(misses_.c_str(), "w"));
        if (!misses) {
            std::fprintf(stderr, "ugv-eval: %s: cannot write\n", misses_.c_str());
            return 2;
        }
    }
    if (pose_ == "truth" && truth_poses.empty()) {
        std::fprintf(stderr, "ugv-eval: %s: no SIM_TRUTH to place the maps with (--pose truth)\n", log_.c_str());
        return 2;
    }
    // The egocentric map is what the vehicle sees around itself: placed with the true pose it
    // is judged on that alone, not on the estimator's error in placing the vehicle (its yaw
    // before the first course over ground is off by up to 0.3 rad).
    auto to_truth = [&](pose_t& p, int64_t utime) {
        if (truth_poses.empty()) return;
        auto it = std::lower_bound(truth_poses.begin(), truth_poses.end(), utime,
                                   [](const sim_truth_t& t, int64_t u) { return t.utime < u; });
        if (it == truth_poses.end()) --it;
        if (it != truth_poses.begin() && std::llabs(std::prev(it)->utime - utime) < std::llabs(it->utime - utime)) --it;
        for (int k = 0; k < 3; ++k) p.position[k] = it->position[k];
        for (int k = 0; k < 4; ++k) p.orientation[k] = it->orientation[k];
    };
    for (traversability_map_t& m : maps) to_truth(m.pose, m.utime);
    for (auto& [seq, a] : arcs) to_truth(a.pose, a.utime);
    TraverseScore total;
    long with_arcs = 0, with_terrain = 0;
    double worst_recall = 2.0, worst_false = -1.0, worst_agreement = 2.0;
    for (const traversability_map_t& m : maps) {
        const PlacedClasses placed(m);
        TraverseScore s;
        // The terrain map it came from, when the log holds it and its grid is the same.
        const SampledExtremes* source = nullptr;
        if (const auto t = terrain.find(m.map_seq); t != terrain.end() && t->second.nx == m.nx &&
                                                   t->second.ny == m.ny && t->second.origin_x == m.origin_x &&
                                                   t->second.origin_y == m.origin_y) {
            source = &t->second;
            ++with_terrain;
        }
        std::vector<char> sampled_cells;
        score_cells(truth, m, placed, source, range_m_, misses.get(), s, sampled_cells);
        const auto it = arcs.find(m.map_seq);
        if (it != arcs.end()) {
            score_arcs(truth, placed, it->second, rear_x_m_, front_x_m_, source != nullptr ? &sampled_cells : nullptr, s);
            ++with_arcs;
        }
        std::printf("{\"utime\": %lld, \"seq\": %lld, \"map_seq\": %lld, %s}\n", static_cast<long long>(m.utime),
                    static_cast<long long>(m.seq), static_cast<long long>(m.map_seq), s.json().c_str());
        const long seen = s.obstacle_seen + s.negative_seen;
        if (seen > 0)
            worst_recall = std::min(worst_recall, double(s.obstacle_detected + s.negative_detected) / double(seen));
        if (s.traversable_known > 0)
            worst_false = std::max(worst_false, double(s.false_obstacles + s.false_negative_obstacles) /
                                                    double(s.traversable_known));
        if (s.arcs > 0) worst_agreement = std::min(worst_agreement, double(s.arcs_agree) / double(s.arcs));
        total.add(s);
    }
    auto worst = [](double v, bool valid) {
        if (!valid) return std::string("null");
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.5f", v);
        return std::string(buf);
    };
    std::printf("{\"summary\": true, \"maps\": %zu, \"maps_with_arcs\": %ld, \"maps_with_terrain\": %ld, "
                "\"malformed\": %ld, \"invalid_maps\": %ld, "
                "\"invalid_arcs\": %ld, \"range_m\": %g, %s, \"worst_recall\": %s, \"worst_false_obstacle_rate\": %s, "
                "\"worst_arc_agreement\": %s}\n",
                maps.size(), with_arcs, with_terrain, malformed, invalid_maps, invalid_arcs, range_m_, total.json().c_str(),
                worst(worst_recall, worst_recall <= 1.0).c_str(), worst(worst_false, worst_false >= 0.0).c_str(),
                worst(worst_agreement, worst_agreement <= 1.0).c_str());
    if (maps.empty()) {
        std::fprintf(stderr, "ugv-eval: no traversability map on %s in %s\n", channel_.c_str(), log_.c_str());
        return 1;
    }
    return 0;
}

}  // namespace ugv::eval
