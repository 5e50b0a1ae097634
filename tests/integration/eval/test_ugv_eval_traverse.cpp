// ugv-eval traverse on logs written here: traversability maps and candidate arcs over a crafted
// truth height field (ground at 1.5 m, and at 0 for the same answer), and `compare` on ground
// at 1.5 m (it used to call every cell an obstacle there).
#include <catch2/catch.hpp>

#include <lcm/lcm-cpp.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "ugv/candidate_arcs_t.hpp"
#include "ugv/simworld/height_field.hpp"
#include "ugv/terrain_map_t.hpp"
#include "ugv/traversability_map_t.hpp"
#include "ugv_test/encoded.hpp"
#include "ugv_test/process.hpp"

using namespace ugv;

namespace {

constexpr int64_t kUtime = 1'700'000'000'000'000;
constexpr double kRes = 0.05;  // truth columns
constexpr float kCell = 0.2f;  // map cells
// The map: 100 x 100 cells of 0.2 m at the identity pose at (0, 0, ground), from (-5, -10):
// cell (i, j) covers x in [-5 + 0.2 i, ...), y in [-10 + 0.2 j, ...). Ahead within 15 m:
// rows 25..99 (centres 0.1 .. 14.9).
constexpr int kN = 100;
constexpr float kOriginX = -5.0f, kOriginY = -10.0f;

struct Box
{
    double x0, y0, x1, y1, h;
};
// Box A (0.6 m, 1 x 1 m, cells aligned) straight ahead at 6 m; box B (0.3 m, 0.4 x 0.4 m) at
// 10 m, 2 m to the left; ditch C (0.4 m deep, 1 x 1 m) at 8 m, 3 m to the right.
const Box kBoxA{6.0, -0.6, 7.0, 0.4, 0.6};
const Box kBoxB{10.0, 2.0, 10.4, 2.4, 0.3};
const Box kDitchC{8.0, -4.0, 9.0, -3.0, -0.4};

simworld::HeightField field(double ground, const std::vector<Box>& boxes)
{
    simworld::HeightField f(-6.0, -11.0, kRes, 440, 440, static_cast<float>(ground));
    for (int i = 0; i < f.nx; ++i)
        for (int j = 0; j < f.ny; ++j)
            for (const Box& b : boxes)
                if (f.cell_x(i) > b.x0 && f.cell_x(i) < b.x1 && f.cell_y(j) > b.y0 && f.cell_y(j) < b.y1)
                    f.at(i, j) = static_cast<float>(ground + b.h);
    return f;
}

// The test's own reading of the rules, for small boxes and ditches on flat ground (the
// slope rule off; the local ground is the flat ground): a column is an obstacle if it stands
// 0.2 m above the ground, negative if it lies 0.2 m below it; a cell takes the worst of its
// columns.
std::vector<int8_t> oracle_classes(const simworld::HeightField& f, double ground)
{
    std::vector<int8_t> cls(kN * kN, traversability_map_t::CLASS_TRAVERSABLE);
    for (int i = 0; i < kN; ++i) {
        for (int j = 0; j < kN; ++j) {
            int8_t worst = traversability_map_t::CLASS_TRAVERSABLE;
            for (int a = 0; a < 4; ++a) {
                for (int b = 0; b < 4; ++b) {
                    const double x = kOriginX + double(kCell) * i + kRes * (a + 0.5), y = kOriginY + double(kCell) * j + kRes * (b + 0.5);
                    const double z = f.height_at(x, y);
                    if (z - ground >= 0.2 - 1e-5) worst = traversability_map_t::CLASS_OBSTACLE;
                    if (ground - z >= 0.2 - 1e-5 && worst != traversability_map_t::CLASS_OBSTACLE)
                        worst = traversability_map_t::CLASS_NEGATIVE_OBSTACLE;
                }
            }
            cls[static_cast<std::size_t>(i * kN + j)] = worst;
        }
    }
    return cls;
}

// The stamp, the identity pose at (0, 0, ground) and the grid above, as both map types
// name them.
template <typename Map>
void place(Map& m, double ground)
{
    m.utime = kUtime;
    m.pose.utime = kUtime;
    m.pose.orientation[0] = 1.0;
    m.pose.position[2] = ground;
    m.resolution = kCell;
    m.nx = m.ny = kN;
    m.origin_x = kOriginX;
    m.origin_y = kOriginY;
    m.ncells = kN * kN;
}

traversability_map_t trav_map(double ground, const std::vector<int8_t>& cls)
{
    traversability_map_t m{};
    place(m, ground);
    m.seq = 1;
    m.map_seq = 7;
    m.cell_class = cls;
    for (auto* layer : {&m.cost, &m.step_m, &m.drop_m, &m.slope_deg, &m.roughness_m, &m.span_m, &m.certainty})
        layer->assign(kN * kN, 0.0f);
    return m;
}

// Arcs right (radius 5 m), straight, left: only the straight one meets box A.
candidate_arcs_t arcs_msg(double ground, std::vector<int8_t> blocked)
{
    candidate_arcs_t a{};
    a.utime = kUtime;
    a.seq = 1;
    a.map_seq = 7;
    a.pose.utime = kUtime;
    a.pose.orientation[0] = 1.0;
    a.pose.position[2] = ground;
    a.length_m = 12.0f;
    a.swept_width_m = 2.2f;
    a.narcs = 3;
    a.curvature = {-0.2f, 0.0f, 0.2f};
    a.clear_distance_m = {12.0f, 12.0f, 12.0f};
    a.unknown_fraction = {0.0f, 0.0f, 0.0f};
    a.mean_cost = {0.0f, 0.0f, 0.0f};
    a.merit = {1.0f, 1.0f, 1.0f};
    a.blocked = std::move(blocked);
    a.best = 0;
    return a;
}

void cell(std::vector<int8_t>& cls, double x, double y, int8_t c)
{
    const int i = static_cast<int>(std::floor((x - kOriginX) / kCell)), j = static_cast<int>(std::floor((y - kOriginY) / kCell));
    cls[static_cast<std::size_t>(i * kN + j)] = c;
}

// Every cell overlapping [x0, x1) x [y0, y1) set to c.
void area(std::vector<int8_t>& cls, double x0, double y0, double x1, double y1, int8_t c)
{
    for (double x = x0 + 0.1; x < x1; x += kCell)
        for (double y = y0 + 0.1; y < y1; y += kCell) cell(cls, x, y, c);
}

// The terrain map a traversability map came from (seq 7, its grid): every cell's samples at
// the ground, those overlapping [x0, x1) x [y0, y1) of `tops` reaching up to ground + h (h < 0:
// down to it).
terrain_map_t source_map(double ground, const std::vector<Box>& tops)
{
    terrain_map_t t{};
    place(t, ground);
    t.seq = 7;
    for (auto* layer : {&t.mean_z, &t.max_z, &t.min_z}) layer->assign(kN * kN, static_cast<float>(ground));
    t.variance_z.assign(kN * kN, 1e-4f);
    t.age_s.assign(kN * kN, 0.0f);
    t.count.assign(kN * kN, 5);
    for (const Box& b : tops) {
        for (double x = b.x0 + 0.1; x < b.x1; x += kCell) {
            for (double y = b.y0 + 0.1; y < b.y1; y += kCell) {
                const auto k = static_cast<std::size_t>(static_cast<int>(std::floor((x - kOriginX) / kCell)) * kN +
                                                        static_cast<int>(std::floor((y - kOriginY) / kCell)));
                (b.h > 0 ? t.max_z : t.min_z)[k] = static_cast<float>(ground + b.h);
            }
        }
    }
    return t;
}

struct Run
{
    int rc = -1;
    std::string out;
    // A number of the last (summary) line.
    double get(const std::string& key) const
    {
        const std::size_t line = out.rfind("{\"summary\"");
        const std::size_t at = out.find("\"" + key + "\": ", line == std::string::npos ? 0 : line);
        if (at == std::string::npos) return NAN;
        const std::string rest = out.substr(at + key.size() + 4);
        return rest.rfind("null", 0) == 0 ? NAN : std::stod(rest);
    }
};

Run eval(const test::TempDir& dir, std::vector<std::string> args)
{
    args.insert(args.begin(), test::bin("ugv-eval"));
    Run r;
    r.rc = test::run(args, dir / "out.txt", dir / "err.txt", 60);
    r.out = test::read_file(dir / "out.txt") + test::read_file(dir / "err.txt");
    return r;
}

struct World
{
    test::TempDir dir;
    simworld::HeightField truth;
    std::vector<int8_t> perfect;
    explicit World(double ground) : truth(field(ground, {kBoxA, kBoxB, kDitchC})), perfect(oracle_classes(truth, ground))
    {
        test::write_file(dir / "truth.hf", simworld::encode_height_field(truth));
    }
    Run score(const traversability_map_t& m, const candidate_arcs_t* a, std::vector<std::string> extra = {},
              const terrain_map_t* source = nullptr)
    {
        const std::string log = dir / "t.lcm";
        {
            lcm::LogFile f(log, "w");
            if (source) test::write_event(f, kUtime, "TERRAIN_MAP", *source);
            test::write_event(f, kUtime, "TRAVERSABILITY_MAP", m);
            if (a) test::write_event(f, kUtime, "ARCS", *a);
        }
        std::vector<std::string> args{"traverse", log, "--truth", dir / "truth.hf", "--max-slope-deg", "89",
                                      "--slope-radius-m", "0.1"};
        args.insert(args.end(), extra.begin(), extra.end());
        return eval(dir, args);
    }
};

}  // namespace

TEST_CASE("ugv-eval traverse: a perfect map on ground at 1.5 m has recall 1, no false obstacle, arcs agree")
{
    World w(1.5);
    // By hand: box A's 25 cells are obstacles, and box B's 4; the ground at their feet is no
    // negative obstacle (it is the local ground). Ditch C: 25 negative cells, its rim no
    // obstacle.
    const std::vector<int8_t>& p = w.perfect;
    long obstacles = 0, negatives = 0;
    for (int8_t c : p) {
        obstacles += c == traversability_map_t::CLASS_OBSTACLE;
        negatives += c == traversability_map_t::CLASS_NEGATIVE_OBSTACLE;
    }
    REQUIRE(obstacles == 25 + 4);
    REQUIRE(negatives == 25);
    const candidate_arcs_t arcs = arcs_msg(1.5, {0, 1, 0});
    const Run r = w.score(trav_map(1.5, p), &arcs);
    INFO(r.out);
    REQUIRE(r.rc == 0);
    CHECK(r.get("maps") == 1);
    CHECK(r.get("obstacle_cells") == 29);
    CHECK(r.get("obstacle_seen") == 29);
    CHECK(r.get("obstacle_detected") == 29);
    CHECK(r.get("negative_cells") == 25);
    CHECK(r.get("negative_detected") == 25);
    CHECK(r.get("recall") == 1.0);
    CHECK(r.get("traversable_known") == 75 * 100 - 54);
    CHECK(r.get("false_obstacles") == 0);
    CHECK(r.get("false_obstacle_rate") == 0.0);
    CHECK(r.get("arcs") == 3);
    CHECK(r.get("arcs_truth_blocked") == 1);
    CHECK(r.get("arc_agreement") == 1.0);
    CHECK(r.get("arc_agreement_unrestricted") == 1.0);

    // The same world with the ground at 0 gives the same counts.
    World w0(0.0);
    const Run r0 = w0.score(trav_map(0.0, w0.perfect), &arcs);
    CHECK(r0.rc == 0);
    CHECK(r0.out.substr(r0.out.find("\"obstacle_cells\"")) == r.out.substr(r.out.find("\"obstacle_cells\"")));

    // Behind the vehicle (body x < 0) nothing counts: the same map turned round (yaw pi).
    traversability_map_t back = trav_map(1.5, p);
    back.pose.orientation[0] = 0.0;
    back.pose.orientation[3] = 1.0;
    back.residual_yaw = 0.0f;
    const Run rb = w.score(back, nullptr);
    CHECK(rb.get("obstacle_cells") == 0);
    CHECK(rb.get("negative_cells") == 0);
}

TEST_CASE("ugv-eval traverse: a missed box lowers the recall by its cells, a false obstacle is counted")
{
    World w(1.5);
    std::vector<int8_t> cls = w.perfect;
    area(cls, 10.0, 2.0, 10.4, 2.4, traversability_map_t::CLASS_TRAVERSABLE);  // box B
    cell(cls, 3.0, -3.0, traversability_map_t::CLASS_OBSTACLE);               // flat ground
    cell(cls, 4.0, -4.0, traversability_map_t::CLASS_NEGATIVE_OBSTACLE);      // flat ground
    // The cell before box A: within one cell of a truth obstacle, no false one.
    cell(cls, 5.9, 0.0, traversability_map_t::CLASS_OBSTACLE);
    const Run r = w.score(trav_map(1.5, cls), nullptr, {"--misses", w.dir / "misses.jsonl"});
    INFO(r.out);
    REQUIRE(r.rc == 0);
    // --misses: a line per missed cell (box B's 4) and per false one (2).
    const std::string misses = test::read_file(w.dir / "misses.jsonl");
    auto lines_with = [&](const std::string& what) {
        int n = 0;
        for (std::size_t at = misses.find(what); at != std::string::npos; at = misses.find(what, at + 1)) ++n;
        return n;
    };
    CHECK(lines_with("\"what\": \"missed\"") == 4);
    CHECK(lines_with("\"what\": \"false\"") == 2);
    CHECK(misses.find("\"x\": 10.10, \"y\": 2.10") != std::string::npos);
    CHECK(r.get("obstacle_seen") == 29);
    CHECK(r.get("obstacle_detected") == 25);
    CHECK(r.get("negative_detected") == 25);
    CHECK(r.get("recall") == Approx(50.0 / 54.0).margin(1e-5));
    CHECK(r.get("false_obstacles") == 1);
    CHECK(r.get("false_negative_obstacles") == 1);
    CHECK(r.get("false_obstacle_rate") == Approx(2.0 / (7500 - 54)).margin(1e-5));
    CHECK(r.get("arcs") == 0);
    CHECK(std::isnan(r.get("arc_agreement")));

    // A box the laser has not seen (its cells UNKNOWN) is not missed: recall back to 1.
    area(cls, 10.0, 2.0, 10.4, 2.4, traversability_map_t::CLASS_UNKNOWN);
    const Run u = w.score(trav_map(1.5, cls), nullptr);
    CHECK(u.get("obstacle_cells") == 29);
    CHECK(u.get("obstacle_seen") == 25);
    CHECK(u.get("recall") == 1.0);
    // Out of --range-m: box A at 6-7 m and B at 10 m are not scored within 5 m.
    const Run near = w.score(trav_map(1.5, cls), nullptr, {"--range-m", "5"});
    CHECK(near.get("obstacle_cells") == 0);
    CHECK(near.get("negative_cells") == 0);
}

TEST_CASE("ugv-eval traverse: the sampled recall counts only obstacles whose height the laser measured")
{
    World w(1.5);
    std::vector<int8_t> cls = w.perfect;
    area(cls, 10.0, 2.0, 10.4, 2.4, traversability_map_t::CLASS_TRAVERSABLE);  // box B missed
    // Box A and the ditch's floor sampled; box B only at its foot (0.1 m of its 0.3 m).
    const terrain_map_t source = source_map(1.5, {kBoxA, kDitchC, {kBoxB.x0, kBoxB.y0, kBoxB.x1, kBoxB.y1, 0.1}});
    Run r = w.score(trav_map(1.5, cls), nullptr, {"--misses", w.dir / "misses.jsonl"}, &source);
    INFO(r.out);
    REQUIRE(r.rc == 0);
    CHECK(r.get("maps_with_terrain") == 1);
    CHECK(r.get("recall") == Approx(50.0 / 54.0).margin(1e-5));
    CHECK(r.get("sampled") == 50);
    CHECK(r.get("sampled_detected") == 50);
    CHECK(r.get("sampled_recall") == 1.0);
    CHECK(test::read_file(w.dir / "misses.jsonl").find("\"max_z\": 1.600, \"min_z\": 1.500, \"sample_threshold_z\": 1.700, "
                                                        "\"sampled\": false") != std::string::npos);
    // Box B seen to its top: sampled, and missed.
    const terrain_map_t topped = source_map(1.5, {kBoxA, kDitchC, kBoxB});
    r = w.score(trav_map(1.5, cls), nullptr, {}, &topped);
    CHECK(r.get("sampled") == 54);
    CHECK(r.get("sampled_recall") == Approx(50.0 / 54.0).margin(1e-5));
    // The ditch's floor in the rim's shadow (no sample below the rim): not sampled.
    const terrain_map_t shadowed = source_map(1.5, {kBoxA, kBoxB});
    r = w.score(trav_map(1.5, cls), nullptr, {}, &shadowed);
    CHECK(r.get("sampled") == 29);
    // A box whose top was sampled but no ground around it was: not sampled.
    terrain_map_t floating = source_map(1.5, {kBoxA, kDitchC, kBoxB});
    for (float& z : floating.min_z)
        if (z >= 1.5f) z = 1.65f;  // every sample above the ground but the ditch's floor
    r = w.score(trav_map(1.5, cls), nullptr, {}, &floating);
    CHECK(r.get("sampled") == 25);  // the ditch only
    // A terrain map of another grid is not paired: nothing sampled.
    terrain_map_t other = source_map(1.5, {kBoxA});
    other.origin_x += kCell;
    r = w.score(trav_map(1.5, cls), nullptr, {}, &other);
    CHECK(r.get("maps_with_terrain") == 0);
    CHECK(r.get("sampled") == 0);
    CHECK(std::isnan(r.get("sampled_recall")));
}

// A 0.4 m ramp rising over x 4 .. 8 m for |y| < half_width_m, then a drop to the ground at 1.5 m
// (also at its sides), scored as a map that knows every cell, sampled at its columns' extremes,
// and calls all traversable, but the cells at x 8 .. 10 m behind the high edge (unknown when
// `shadowed`; with `top_strip`, the first row of them known, holding only samples of the top, as
// the edge's returns spread by the pose's error). The truth's local ground of the top's last half
// metre takes in the ground behind the edge. Returns the run and the sampled misses within 0.5 m of
// the ramp's centre line.
struct RampScore
{
    Run run;
    int sampled_middle = 0;
};

RampScore score_ramp(double half_width_m, bool shadowed, bool top_strip = false)
{
    test::TempDir dir;
    simworld::HeightField f(-6.0, -11.0, kRes, 440, 440, 1.5f);
    for (int i = 0; i < f.nx; ++i)
        for (int j = 0; j < f.ny; ++j)
            if (f.cell_x(i) > 4.0 && f.cell_x(i) < 8.0 && std::abs(f.cell_y(j)) < half_width_m)
                f.at(i, j) = static_cast<float>(1.5 + 0.1 * (f.cell_x(i) - 4.0));
    test::write_file(dir / "truth.hf", simworld::encode_height_field(f));
    terrain_map_t t = source_map(1.5, {});
    for (int i = 0; i < kN; ++i)
        for (int j = 0; j < kN; ++j) {
            const std::size_t k = static_cast<std::size_t>(i * kN + j);
            for (int a = 0; a < 4; ++a)
                for (int b = 0; b < 4; ++b) {
                    const auto z = static_cast<float>(f.height_at(kOriginX + double(kCell) * i + kRes * (a + 0.5),
                                                                  kOriginY + double(kCell) * j + kRes * (b + 0.5)));
                    t.max_z[k] = std::max(a + b == 0 ? z : t.max_z[k], z);
                    t.min_z[k] = std::min(a + b == 0 ? z : t.min_z[k], z);
                }
        }
    std::vector<int8_t> cls(kN * kN, traversability_map_t::CLASS_TRAVERSABLE);
    if (shadowed)
        area(cls, top_strip ? 8.0 + double(kCell) : 8.0, kOriginY, 10.0, kOriginY + kN * double(kCell),
             traversability_map_t::CLASS_UNKNOWN);
    if (top_strip) {
        const int row = static_cast<int>(std::lround((8.0 - kOriginX) / double(kCell)));
        for (int j = 0; j < kN; ++j) {
            const std::size_t k = static_cast<std::size_t>(row * kN + j);
            if (std::abs(kOriginY + double(kCell) * (j + 0.5)) < half_width_m) t.min_z[k] = t.max_z[k] = 1.9f;
        }
    }
    const std::string log = dir / "t.lcm";
    {
        lcm::LogFile out(log, "w");
        test::write_event(out, kUtime, "TERRAIN_MAP", t);
        test::write_event(out, kUtime, "TRAVERSABILITY_MAP", trav_map(1.5, cls));
    }
    RampScore r{eval(dir, {"traverse", log, "--truth", dir / "truth.hf", "--misses", dir / "misses.jsonl"}), 0};
    const std::string misses = test::read_file(dir / "misses.jsonl");
    for (std::size_t at = misses.find("\"body_y\": "); at != std::string::npos; at = misses.find("\"body_y\": ", at + 1)) {
        const std::size_t line_end = misses.find('\n', at);
        if (std::abs(std::stod(misses.substr(at + 10))) < 0.5 &&
            misses.substr(at, line_end - at).find("\"sampled\": true") != std::string::npos)
            ++r.sampled_middle;
    }
    return r;
}

TEST_CASE("ugv-eval traverse: a ramp's top is sampled only when the ground behind its high edge was seen")
{
    // Across the whole field.
    const RampScore seen = score_ramp(100.0, false);
    INFO(seen.run.out);
    REQUIRE(seen.run.rc == 0);
    CHECK(seen.run.get("obstacle_seen") > 0);  // the top's last cells, by the truth's ground
    CHECK(seen.run.get("sampled") > 0);        // the ground behind the edge seen: a step over it
    CHECK(seen.sampled_middle > 0);
    CHECK(seen.run.get("sampled_recall") == 0.0);
    // The ground behind the edge in its shadow (unknown): the top is no step over what was seen.
    const RampScore shadowed = score_ramp(100.0, true);
    INFO(shadowed.run.out);
    CHECK(shadowed.run.get("obstacle_seen") == seen.run.get("obstacle_seen"));
    CHECK(shadowed.run.get("sampled") == 0);
}

TEST_CASE("ugv-eval traverse: whether a seen column is ground is judged on what was seen")
{
    // A 2.4 m wide ramp, the ground at its sides seen, the ground behind its high edge not: by the
    // whole truth the top's last half metre stands over the ground behind the edge, but over
    // what was seen the middle of the top is the ramp's own ground, and no step.
    const RampScore shadowed = score_ramp(1.2, true);
    INFO(shadowed.run.out);
    REQUIRE(shadowed.run.rc == 0);
    CHECK(shadowed.run.get("obstacle_seen") > 0);
    CHECK(shadowed.sampled_middle == 0);
    // The ground behind the edge seen: the middle of the top is a step over it again.
    const RampScore seen = score_ramp(1.2, false);
    INFO(seen.run.out);
    CHECK(seen.sampled_middle > 0);
    // A known cell's ground is seen only where its samples reach it: the row behind the edge
    // known for samples of the top alone has not seen the ground at the edge's foot.
    const RampScore strip = score_ramp(1.2, true, true);
    INFO(strip.run.out);
    REQUIRE(strip.run.rc == 0);
    CHECK(strip.sampled_middle == 0);
}

TEST_CASE("ugv-eval traverse: arcs against the truth, sampled, seen by the laser and unrestricted")
{
    World w(1.5);
    // The map says the left arc is blocked too: 2 of 3 agree.
    candidate_arcs_t arcs = arcs_msg(1.5, {0, 1, 1});
    Run r = w.score(trav_map(1.5, w.perfect), &arcs);
    INFO(r.out);
    CHECK(r.get("arcs_blocked") == 2);
    CHECK(r.get("arcs_agree") == 2);
    CHECK(r.get("arc_agreement") == Approx(2.0 / 3.0).margin(1e-5));
    // Box A unseen (UNKNOWN): the seen truth says the straight arc is free; every column says blocked.
    std::vector<int8_t> cls = w.perfect;
    area(cls, 5.6, -1.0, 7.4, 0.8, traversability_map_t::CLASS_UNKNOWN);
    arcs = arcs_msg(1.5, {0, 0, 0});
    r = w.score(trav_map(1.5, cls), &arcs);
    CHECK(r.get("arcs_truth_blocked") == 0);
    CHECK(r.get("arc_agreement") == 1.0);
    CHECK(r.get("arcs_truth_blocked_unrestricted") == 1);
    CHECK(r.get("arc_agreement_unrestricted") == Approx(2.0 / 3.0).margin(1e-5));
    // Against the sampled truth, with the terrain map: box A sampled to its top blocks the
    // straight arc; sampled only at its foot (0.1 m of its 0.6 m) it does not, though seen.
    arcs = arcs_msg(1.5, {0, 1, 0});
    const terrain_map_t topped = source_map(1.5, {kBoxA, kDitchC, kBoxB});
    r = w.score(trav_map(1.5, w.perfect), &arcs, {}, &topped);
    CHECK(r.get("arcs_with_terrain") == 3);
    CHECK(r.get("arcs_truth_blocked_sampled") == 1);
    CHECK(r.get("arc_agreement_sampled") == 1.0);
    const terrain_map_t foot = source_map(1.5, {{kBoxA.x0, kBoxA.y0, kBoxA.x1, kBoxA.y1, 0.1}, kDitchC, kBoxB});
    r = w.score(trav_map(1.5, w.perfect), &arcs, {}, &foot);
    CHECK(r.get("arcs_truth_blocked") == 1);
    CHECK(r.get("arcs_truth_blocked_sampled") == 0);
    CHECK(r.get("arc_agreement_sampled") == Approx(2.0 / 3.0).margin(1e-5));
    // Without the terrain map there is no sampled truth.
    r = w.score(trav_map(1.5, w.perfect), &arcs);
    CHECK(r.get("arcs_with_terrain") == 0);
    CHECK(std::isnan(r.get("arc_agreement_sampled")));
    // Arcs of another terrain map are not paired with this one.
    arcs.map_seq = 8;
    r = w.score(trav_map(1.5, cls), &arcs);
    CHECK(r.get("arcs") == 0);
    CHECK(r.get("maps_with_arcs") == 0);
}

TEST_CASE("ugv-eval traverse: NaN and garbage in the log are counted, not scored, never a crash")
{
    World w(1.5);
    const std::string log = w.dir / "bad.lcm";
    {
        lcm::LogFile f(log, "w");
        traversability_map_t nan_pose = trav_map(1.5, w.perfect);
        nan_pose.pose.position[0] = NAN;
        test::write_event(f, kUtime, "TRAVERSABILITY_MAP", nan_pose);
        traversability_map_t bad_class = trav_map(1.5, w.perfect);
        bad_class.cell_class[17] = 9;
        test::write_event(f, kUtime, "TRAVERSABILITY_MAP", bad_class);
        traversability_map_t nan_res = trav_map(1.5, w.perfect);
        nan_res.resolution = NAN;
        test::write_event(f, kUtime, "TRAVERSABILITY_MAP", nan_res);
        std::vector<uint8_t> truncated = test::encoded(trav_map(1.5, w.perfect));
        truncated.resize(truncated.size() / 3);
        lcm::LogEvent ev{};
        ev.timestamp = kUtime;
        ev.channel = "TRAVERSABILITY_MAP";
        ev.datalen = static_cast<int32_t>(truncated.size());
        ev.data = truncated.data();
        f.writeEvent(&ev);
        ev.channel = "ARCS";
        f.writeEvent(&ev);
        candidate_arcs_t nan_arcs = arcs_msg(1.5, {0, 1, 0});
        nan_arcs.curvature[1] = NAN;
        test::write_event(f, kUtime, "ARCS", nan_arcs);
        test::write_event(f, kUtime, "TRAVERSABILITY_MAP", trav_map(1.5, w.perfect));
    }
    Run r = eval(w.dir, {"traverse", log, "--truth", w.dir / "truth.hf", "--max-slope-deg", "89", "--slope-radius-m", "0.1"});
    INFO(r.out);
    CHECK(r.rc == 0);
    CHECK(r.get("maps") == 1);
    CHECK(r.get("malformed") == 2);
    CHECK(r.get("invalid_maps") == 3);
    CHECK(r.get("invalid_arcs") == 1);
    CHECK(r.get("recall") == 1.0);
    CHECK(r.out.find("cell class out of range") != std::string::npos);
    // Only garbage: no map, exit 1; a truth that is not a height field: exit 2.
    const std::string only_bad = w.dir / "only_bad.lcm";
    {
        lcm::LogFile f(only_bad, "w");
        traversability_map_t nan_pose = trav_map(1.5, w.perfect);
        nan_pose.pose.orientation[0] = NAN;
        test::write_event(f, kUtime, "TRAVERSABILITY_MAP", nan_pose);
    }
    r = eval(w.dir, {"traverse", only_bad, "--truth", w.dir / "truth.hf"});
    CHECK(r.rc == 1);
    CHECK(r.get("maps") == 0);
    test::write_file(w.dir / "bad.hf", "P5\n");
    CHECK(eval(w.dir, {"traverse", log, "--truth", w.dir / "bad.hf"}).rc == 2);
}

TEST_CASE("ugv-eval compare: obstacles stand above the local ground, wherever the ground is")
{
    // Ground at 1.5 m with a 0.4 m wide, 0.5 m tall ridge across x in [2.3, 2.7); a 4 x 4 map
    // of 1 m cells from (0, -2): the cells i = 2 hold the ridge.
    test::TempDir dir;
    simworld::HeightField truth(-1.0, -3.0, 0.05, 120, 120, 1.5f);
    for (int i = 0; i < truth.nx; ++i)
        for (int j = 0; j < truth.ny; ++j)
            if (truth.cell_x(i) > 2.3 && truth.cell_x(i) < 2.7) truth.at(i, j) = 2.0f;
    test::write_file(dir / "truth.hf", simworld::encode_height_field(truth));
    terrain_map_t m{};
    m.utime = kUtime;
    m.pose.utime = kUtime;
    m.pose.orientation[0] = 1.0;
    m.resolution = 1.0f;
    m.nx = m.ny = 4;
    m.origin_x = 0.0f;
    m.origin_y = -2.0f;
    m.ncells = 16;
    m.mean_z.assign(16, 1.52f);
    for (int j = 0; j < 4; ++j) m.mean_z[static_cast<std::size_t>(2 * 4 + j)] = 2.0f;
    m.variance_z.assign(16, 0.01f);
    m.count.assign(16, 5);
    m.max_z = m.mean_z;
    m.min_z = m.mean_z;
    m.age_s.assign(16, 0.0f);
    const std::string log = dir / "map.lcm";
    {
        lcm::LogFile f(log, "w");
        test::write_event(f, kUtime, "TERRAIN_MAP", m);
    }
    Run r = eval(dir, {"compare", log, "--truth", dir / "truth.hf"});
    INFO(r.out);
    REQUIRE(r.rc == 0);
    CHECK(r.out.find("\"obstacle_cells\": 4,") != std::string::npos);
    CHECK(r.out.find("\"obstacles_detected\": 4,") != std::string::npos);
    CHECK(r.out.find("\"false_obstacles\": 0,") != std::string::npos);
    // --flat 1.5 with the ridge as a box: the same.
    r = eval(dir, {"compare", log, "--flat", "1.5", "--box", "2.3,-5,2.7,5,2.0"});
    CHECK(r.out.find("\"obstacle_cells\": 4,") != std::string::npos);
    CHECK(r.out.find("\"false_obstacles\": 0,") != std::string::npos);
}

TEST_CASE("ugv-eval traverse: the truth's slopes: 30 degrees is an obstacle, 10 degrees is not")
{
    // Ground at 1.5 m rising at 30 degrees over x in [3, 5), then at 10 degrees over [8, 11),
    // flat between and after, across the whole field (no side edges). Every cell known.
    test::TempDir dir;
    simworld::HeightField truth(-6.0, -11.0, kRes, 440, 440, 1.5f);
    const double steep = std::tan(30.0 * M_PI / 180.0), gentle = std::tan(10.0 * M_PI / 180.0);
    for (int i = 0; i < truth.nx; ++i) {
        const double x = truth.cell_x(i);
        const double z = 1.5 + steep * std::clamp(x - 3.0, 0.0, 2.0) + gentle * std::clamp(x - 8.0, 0.0, 3.0);
        for (int j = 0; j < truth.ny; ++j) truth.at(i, j) = static_cast<float>(z);
    }
    test::write_file(dir / "truth.hf", simworld::encode_height_field(truth));
    const std::string log = dir / "t.lcm";
    {
        lcm::LogFile f(log, "w");
        test::write_event(f, kUtime, "TRAVERSABILITY_MAP",
                          trav_map(1.5, std::vector<int8_t>(kN * kN, traversability_map_t::CLASS_TRAVERSABLE)));
    }
    const Run all = eval(dir, {"traverse", log, "--truth", dir / "truth.hf"});
    INFO(all.out);
    REQUIRE(all.rc == 0);
    const double obstacles = all.get("obstacle_cells");
    // The 2 m steep band is 10 rows of 100 cells; near the bends the plane over 0.5 m also
    // holds flat ground and is less steep: a row or two fewer at each end.
    CHECK(obstacles >= 600);
    CHECK(obstacles <= 1000);
    CHECK(std::fmod(obstacles, 100.0) == 0.0);
    CHECK(all.get("negative_cells") == 0);
    CHECK(all.get("obstacle_detected") == 0);
    // Nothing beyond 7 m: the 10 degree slope is no obstacle.
    const Run near = eval(dir, {"traverse", log, "--truth", dir / "truth.hf", "--range-m", "7"});
    CHECK(near.get("obstacle_cells") == obstacles);
    // A 35 degree limit passes the 30 degree band too.
    const Run lax = eval(dir, {"traverse", log, "--truth", dir / "truth.hf", "--max-slope-deg", "35"});
    CHECK(lax.get("obstacle_cells") == 0);
}
