#include "map_diff.hpp"

#include <lcm/lcm-cpp.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

#include <ugv/terrain_map_t.hpp>

#include "ugv/bus/typed.hpp"
#include "ugv/geometry/rotation.hpp"

namespace ugv::eval {
namespace {

// A map placed in the world: its axes are the body's turned by -residual_yaw, i.e. at world
// yaw (vehicle yaw - residual_yaw), and its origin is the pose's position.
class PlacedMap
{
public:
    explicit PlacedMap(const terrain_map_t& m) : m_(m)
    {
        const double* q = m.pose.orientation;  // w, x, y, z
        const double yaw = geometry::yaw_from_quaternion(Eigen::Quaterniond(q[0], q[1], q[2], q[3]));
        cos_ = std::cos(yaw - m.residual_yaw);
        sin_ = std::sin(yaw - m.residual_yaw);
    }
    int nx() const { return m_.nx; }
    int ny() const { return m_.ny; }
    float z(int i, int j) const { return m_.mean_z[static_cast<std::size_t>(i * m_.ny + j)]; }
    void centre_world(int i, int j, double& x, double& y) const
    {
        const double mx = m_.origin_x + (i + 0.5) * m_.resolution, my = m_.origin_y + (j + 0.5) * m_.resolution;
        x = m_.pose.position[0] + cos_ * mx - sin_ * my;
        y = m_.pose.position[1] + sin_ * mx + cos_ * my;
    }
    // The cell containing world point (x, y); false outside the map.
    bool cell_at(double x, double y, int& i, int& j) const
    {
        const double dx = x - m_.pose.position[0], dy = y - m_.pose.position[1];
        const double mx = cos_ * dx + sin_ * dy, my = -sin_ * dx + cos_ * dy;
        i = static_cast<int>(std::floor((mx - m_.origin_x) / m_.resolution));
        j = static_cast<int>(std::floor((my - m_.origin_y) / m_.resolution));
        return i >= 0 && i < m_.nx && j >= 0 && j < m_.ny;
    }

private:
    const terrain_map_t& m_;
    double cos_ = 1.0, sin_ = 0.0;
};

struct PairDiff
{
    long both = 0, only_a = 0, only_b = 0;
    double max_abs_dz = 0.0, sum_dz2 = 0.0;
    double one_sided() const
    {
        const long any = both + only_a + only_b;
        return any ? static_cast<double>(only_a + only_b) / static_cast<double>(any) : 0.0;
    }
    void add(const PairDiff& o)
    {
        both += o.both, only_a += o.only_a, only_b += o.only_b;
        max_abs_dz = std::max(max_abs_dz, o.max_abs_dz);
        sum_dz2 += o.sum_dz2;
    }
    double rms() const { return both ? std::sqrt(sum_dz2 / static_cast<double>(both)) : 0.0; }
};

// Every cell of b whose centre lies inside a, against a's cell there.
PairDiff diff_maps(const terrain_map_t& a, const terrain_map_t& b)
{
    const PlacedMap pa(a), pb(b);
    PairDiff d;
    for (int i = 0; i < pb.nx(); ++i) {
        for (int j = 0; j < pb.ny(); ++j) {
            double x, y;
            int ia, ja;
            pb.centre_world(i, j, x, y);
            if (!pa.cell_at(x, y, ia, ja)) continue;
            const float za = pa.z(ia, ja), zb = pb.z(i, j);
            if (std::isnan(za) && std::isnan(zb)) continue;
            if (std::isnan(za)) ++d.only_b;
            else if (std::isnan(zb)) ++d.only_a;
            else {
                const double dz = static_cast<double>(za) - static_cast<double>(zb);
                ++d.both;
                d.max_abs_dz = std::max(d.max_abs_dz, std::abs(dz));
                d.sum_dz2 += dz * dz;
            }
        }
    }
    return d;
}

// The maps of a log by utime (the time of the pose each refers to); false when unreadable.
bool read_maps(const std::string& path, const std::string& channel, std::map<int64_t, terrain_map_t>& maps)
{
    lcm::LogFile log(path, "r");
    if (!log.good()) return false;
    while (const lcm::LogEvent* ev = log.readNextEvent()) {
        if (ev->channel != channel) continue;
        terrain_map_t m;
        if (ugv::bus::decode_checked(ev->data, static_cast<std::size_t>(ev->datalen), m)) maps[m.utime] = std::move(m);
    }
    return true;
}

}  // namespace

MapDiffCommand::MapDiffCommand(CLI::App& app)
{
    sub_ = app.add_subcommand("diff", "the maps of two logs, cell by cell at the same world place");
    sub_->add_option("a", log_a_, "first LCM log")->required()->check(CLI::ExistingFile);
    sub_->add_option("b", log_b_, "second LCM log")->required()->check(CLI::ExistingFile);
    sub_->add_option("--channel", channel_, "channel of the maps");
    sub_->add_option("--pair", pair_, "time: maps referring to the same pose time; last: the last map of each")
        ->check(CLI::IsMember({"time", "last"}));
    sub_->add_option("--max-dz", max_dz_m_, "largest |height difference| allowed in a cell known in both (m)");
    sub_->add_option("--max-rms-dz", max_rms_dz_m_, "largest RMS height difference over the cells known in both (m)");
    sub_->add_option("--max-one-sided", max_one_sided_, "largest fraction of cells known in one map only");
    sub_->add_flag("--all", all_, "a line for every pair, not only the summary");
}

int MapDiffCommand::run() const
{
    std::map<int64_t, terrain_map_t> a, b;
    for (const auto& [path, maps] : {std::pair{&log_a_, &a}, std::pair{&log_b_, &b}}) {
        if (!read_maps(*path, channel_, *maps)) {
            std::fprintf(stderr, "ugv-eval: %s: not an LCM log\n", path->c_str());
            return 2;
        }
    }
    std::vector<std::pair<const terrain_map_t*, const terrain_map_t*>> pairs;
    if (pair_ == "last") {
        if (!a.empty() && !b.empty()) pairs.emplace_back(&a.rbegin()->second, &b.rbegin()->second);
    } else {
        for (const auto& [t, m] : a)
            if (auto it = b.find(t); it != b.end()) pairs.emplace_back(&m, &it->second);
    }
    PairDiff total;
    double worst_one_sided = 0.0;
    for (const auto& [ma, mb] : pairs) {
        const PairDiff d = diff_maps(*ma, *mb);
        if (all_)
            std::printf("{\"utime_a\": %lld, \"utime_b\": %lld, \"cells_both\": %ld, \"only_a\": %ld, \"only_b\": %ld, "
                        "\"max_abs_dz_m\": %.6f, \"rms_dz_m\": %.6f}\n",
                        static_cast<long long>(ma->utime), static_cast<long long>(mb->utime), d.both, d.only_a,
                        d.only_b, d.max_abs_dz, d.rms());
        worst_one_sided = std::max(worst_one_sided, d.one_sided());
        total.add(d);
    }
    auto within = [](double value, double limit) { return limit < 0.0 || value <= limit; };
    const bool pass = !pairs.empty() && within(total.max_abs_dz, max_dz_m_) && within(total.rms(), max_rms_dz_m_) &&
                      within(worst_one_sided, max_one_sided_);
    std::printf("{\"maps_a\": %zu, \"maps_b\": %zu, \"pairs\": %zu, \"cells_both\": %ld, \"only_a\": %ld, "
                "\"only_b\": %ld, \"max_abs_dz_m\": %.6f, \"rms_dz_m\": %.6f, \"worst_one_sided\": %.5f, "
                "\"max_dz_allowed_m\": %g, \"max_rms_dz_allowed_m\": %g, \"max_one_sided_allowed\": %g, \"pass\": %s}\n",
                a.size(), b.size(), pairs.size(), total.both, total.only_a, total.only_b, total.max_abs_dz, total.rms(),
                worst_one_sided, max_dz_m_, max_rms_dz_m_, max_one_sided_, pass ? "true" : "false");
    return pass ? 0 : 1;
}

}  // namespace ugv::eval
