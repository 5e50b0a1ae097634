#include "truth_terrain.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace ugv::eval {
namespace {

// Heights are float32: a 0.2 m box on ground at 1.5 m stands 0.19999999 m tall in them.
constexpr double kHeightTolerance = 1e-5;

std::vector<std::pair<int, int>> disc(double radius_m, double resolution_m)
{
    const int r = static_cast<int>(std::floor(radius_m / resolution_m + 1e-9));
    const double r2 = (radius_m / resolution_m) * (radius_m / resolution_m) + 1e-9;
    std::vector<std::pair<int, int>> out;
    for (int di = -r; di <= r; ++di)
        for (int dj = -r; dj <= r; ++dj)
            if (di * di + dj * dj <= r2) out.emplace_back(di, dj);
    return out;
}

}  // namespace

TruthTerrain::TruthTerrain(std::shared_ptr<const simworld::HeightField> field, const TruthRules& rules)
    : field_(std::move(field)), rules_(rules)
{
    for (double v : {rules.max_step_m, rules.max_drop_m, rules.step_radius_m, rules.ground_radius_m, rules.slope_radius_m})
        if (!(v > 0.0 && std::isfinite(v))) throw std::invalid_argument("truth rules: lengths must be positive");
    if (!(rules.max_slope_deg > 0.0 && rules.max_slope_deg < 90.0))
        throw std::invalid_argument("truth rules: the slope limit must lie between 0 and 90 degrees");
    step_disc_ = disc(rules.step_radius_m, field_->resolution_m);
    slope_disc_ = disc(rules.slope_radius_m, field_->resolution_m);
    for (const auto& [di, dj] : slope_disc_) slope_d2_ += di * di;
    max_slope_tan_ = std::tan(rules.max_slope_deg * M_PI / 180.0);
    for (const auto& o : disc(rules.ground_radius_m, field_->resolution_m))
        if (o.first % 3 == 0 && o.second % 3 == 0) ground_disc_.push_back(o);
    cache_.assign(static_cast<std::size_t>(field_->nx) * static_cast<std::size_t>(field_->ny), 0);
    step_cache_ = cache_;
    ground_done_ = cache_;
    ground_cache_.assign(cache_.size(), std::numeric_limits<double>::quiet_NaN());
}

bool TruthTerrain::column_of(double x_m, double y_m, int& i, int& j) const
{
    const double fi = std::floor((x_m - field_->origin_x_m) / field_->resolution_m);
    const double fj = std::floor((y_m - field_->origin_y_m) / field_->resolution_m);
    if (!(fi >= 0 && fi < field_->nx && fj >= 0 && fj < field_->ny)) return false;  // NaN fails too
    i = static_cast<int>(fi);
    j = static_cast<int>(fj);
    return true;
}

TruthClass TruthTerrain::column_class(int i, int j) const
{
    if (i < 0 || i >= field_->nx || j < 0 || j >= field_->ny) return TruthClass::none;
    uint8_t& slot = cache_[static_cast<std::size_t>(i) * static_cast<std::size_t>(field_->ny) + static_cast<std::size_t>(j)];
    if (slot == 0) slot = static_cast<uint8_t>(static_cast<uint8_t>(compute(i, j)) + 1);
    return static_cast<TruthClass>(slot - 1);
}

TruthClass TruthTerrain::class_at(double x_m, double y_m) const
{
    int i, j;
    return column_of(x_m, y_m, i, j) ? column_class(i, j) : TruthClass::none;
}

double TruthTerrain::local_ground_at(double x_m, double y_m) const
{
    int i, j;
    if (!column_of(x_m, y_m, i, j)) return std::numeric_limits<double>::quiet_NaN();
    double low = std::numeric_limits<double>::quiet_NaN();
    for (const auto& [di, dj] : step_disc_) {
        const int a = i + di, b = j + dj;
        if (a < 0 || a >= field_->nx || b < 0 || b >= field_->ny) continue;
        const double z = field_->at(a, b);
        if (std::isfinite(z) && !(z >= low)) low = z;
    }
    return low;
}

double TruthTerrain::ground_height(int i, int j) const
{
    const simworld::HeightField& f = *field_;
    if (i < 0 || i >= f.nx || j < 0 || j >= f.ny) return std::numeric_limits<double>::quiet_NaN();
    const std::size_t k = static_cast<std::size_t>(i) * static_cast<std::size_t>(f.ny) + static_cast<std::size_t>(j);
    if (ground_done_[k] != 0) return ground_cache_[k];
    ground_done_[k] = 1;
    return ground_cache_[k] = ground_over(i, j, nullptr);
}

double TruthTerrain::ground_height_over(int i, int j, const std::function<bool(int, int)>& include) const
{
    const simworld::HeightField& f = *field_;
    if (i < 0 || i >= f.nx || j < 0 || j >= f.ny) return std::numeric_limits<double>::quiet_NaN();
    return ground_over(i, j, &include);
}

double TruthTerrain::ground_over(int i, int j, const std::function<bool(int, int)>* include) const
{
    const simworld::HeightField& f = *field_;
    const double z = f.at(i, j);
    if (!std::isfinite(z)) return std::numeric_limits<double>::quiet_NaN();
    // The columns within ground_radius (every third), the plane through them by least
    // squares, its slope taken out, and the median of what is left (a box or ditch narrower
    // than the radius is the minority; a slope is its own ground).
    if (scratch_.size() <= depth_) scratch_.resize(depth_ + 1);
    std::vector<float>& around = scratch_[depth_].around;
    std::vector<std::pair<int, int>>& offsets = scratch_[depth_].offsets;
    struct Depth
    {
        std::size_t& d;
        explicit Depth(std::size_t& depth) : d(++depth) {}
        ~Depth() { --d; }
    } depth(depth_);
    around.clear();
    offsets.clear();
    double s0 = 0, sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0, sz = 0, saz = 0, sbz = 0;
    for (const auto& [di, dj] : ground_disc_) {
        const int a = i + di, b = j + dj;
        if (a < 0 || a >= f.nx || b < 0 || b >= f.ny) continue;
        const double h = f.at(a, b);
        if (!std::isfinite(h)) continue;
        if (include != nullptr && !(*include)(a, b)) continue;
        const double dz = h - z;
        around.push_back(static_cast<float>(dz));
        offsets.emplace_back(di, dj);
        s0 += 1;
        sa += di;
        sb += dj;
        saa += di * di;
        sbb += dj * dj;
        sab += di * dj;
        sz += dz;
        saz += di * dz;
        sbz += dj * dz;
    }
    double ga = 0, gb = 0;
    const double caa = saa - sa * sa / std::max(s0, 1.0), cbb = sbb - sb * sb / std::max(s0, 1.0);
    const double cab = sab - sa * sb / std::max(s0, 1.0), det = caa * cbb - cab * cab;
    if (s0 >= 6 && det > 1e-9 * s0 * s0) {
        ga = (cbb * (saz - sa * sz / s0) - cab * (sbz - sb * sz / s0)) / det;
        gb = (caa * (sbz - sb * sz / s0) - cab * (saz - sa * sz / s0)) / det;
    }
    for (std::size_t u = 0; u < around.size(); ++u)
        around[u] -= static_cast<float>(ga * offsets[u].first + gb * offsets[u].second);
    if (around.empty()) return include != nullptr ? std::numeric_limits<double>::quiet_NaN() : z;
    double ground = z;
    {
        const auto mid = around.begin() + static_cast<std::ptrdiff_t>(around.size() / 2);
        std::nth_element(around.begin(), mid, around.end());
        ground = z + static_cast<double>(*mid);
    }
    return ground;
}

TruthClass TruthTerrain::step_class(int i, int j) const
{
    const simworld::HeightField& f = *field_;
    uint8_t& slot = step_cache_[static_cast<std::size_t>(i) * static_cast<std::size_t>(f.ny) + static_cast<std::size_t>(j)];
    if (slot != 0) return static_cast<TruthClass>(slot - 1);
    TruthClass out = TruthClass::none;
    const double z = f.at(i, j), ground = ground_height(i, j);
    if (std::isfinite(z) && std::isfinite(ground)) {
        // The column is an obstacle standing max_step above its local ground, a negative one
        // lying max_drop below.
        out = TruthClass::traversable;
        if (z - ground >= rules_.max_step_m - kHeightTolerance) out = TruthClass::obstacle;
        else if (ground - z >= rules_.max_drop_m - kHeightTolerance) out = TruthClass::negative;
    }
    slot = static_cast<uint8_t>(static_cast<uint8_t>(out) + 1);
    return out;
}

TruthClass TruthTerrain::compute(int i, int j) const
{
    const TruthClass step = step_class(i, j);
    if (step != TruthClass::traversable) return step;
    // Too steep is an obstacle where no step obstacle lies within the slope disc (a box
    // would tilt the plane of the ground beside it). Least-squares plane z = c0 + c1 dx + c2 dy:
    // over a whole disc (symmetric: the sums of dx, dy and dx dy vanish) the gradient is
    // sum(d h) / sum(d^2); a disc cut by the field's edge or a missing height takes the
    // general solve.
    const simworld::HeightField& f = *field_;
    const double z = f.at(i, j);
    double sum_i = 0.0, sum_j = 0.0;
    std::size_t n = 0;
    for (const auto& [di, dj] : slope_disc_) {
        const int a = i + di, b = j + dj;
        if (a < 0 || a >= f.nx || b < 0 || b >= f.ny) continue;
        const double h = f.at(a, b);
        if (!std::isfinite(h)) continue;
        if (step_class(a, b) != TruthClass::traversable) return TruthClass::traversable;
        sum_i += di * (h - z);
        sum_j += dj * (h - z);
        ++n;
    }
    double gradient = 0.0;
    if (n == slope_disc_.size()) {
        gradient = std::hypot(sum_i, sum_j) / (slope_d2_ * f.resolution_m);
    } else if (n >= 3) {
        Eigen::Matrix3d ata = Eigen::Matrix3d::Zero();
        Eigen::Vector3d atz = Eigen::Vector3d::Zero();
        for (const auto& [di, dj] : slope_disc_) {
            const int a = i + di, b = j + dj;
            if (a < 0 || a >= f.nx || b < 0 || b >= f.ny) continue;
            const double h = f.at(a, b);
            if (!std::isfinite(h)) continue;
            const Eigen::Vector3d row(1.0, di * f.resolution_m, dj * f.resolution_m);
            ata += row * row.transpose();
            atz += row * (h - z);
        }
        const Eigen::Vector3d c = ata.ldlt().solve(atz);
        if (std::isfinite(c[1]) && std::isfinite(c[2])) gradient = std::hypot(c[1], c[2]);
    }
    return gradient > max_slope_tan_ ? TruthClass::obstacle : TruthClass::traversable;
}

SeenGround::SeenGround(const TruthTerrain& truth, std::function<bool(int, int)> seen)
    : truth_(truth), seen_(std::move(seen))
{
}

double SeenGround::ground(int i, int j) const
{
    return truth_.ground_height_over(i, j, [this](int a, int b) { return seen_(a, b) && !step_over_seen(a, b); });
}

bool SeenGround::step_over_seen(int a, int b) const
{
    const std::int64_t key = static_cast<std::int64_t>(a) * truth_.field().ny + b;
    const auto found = step_.find(key);
    if (found != step_.end()) return found->second;
    const double ground = truth_.ground_height_over(a, b, seen_);
    const bool step = std::isfinite(ground) && truth_.field().at(a, b) - ground >= truth_.rules().max_step_m - kHeightTolerance;
    step_.emplace(key, step);
    return step;
}

}  // namespace ugv::eval
