// ugv-render on logs written here: --traverse pairs each traversability map with the arcs of
// the same terrain map, counts and skips what does not decode, and says when a map has no
// arcs; the height picture's options that do not go together are refused.
#include <catch2/catch.hpp>

#include <lcm/lcm-cpp.hpp>

#include <filesystem>
#include <string>
#include <vector>

#include "ugv/candidate_arcs_t.hpp"
#include "ugv/terrain_map_t.hpp"
#include "ugv/traversability_map_t.hpp"
#include "ugv_test/encoded.hpp"
#include "ugv_test/process.hpp"

using namespace ugv;

namespace {

constexpr int64_t kUtime = 1'700'000'000'000'000;

// 20 x 30 cells of 0.1 m, all traversable.
traversability_map_t map_of(int64_t map_seq)
{
    traversability_map_t m{};
    m.utime = kUtime + map_seq * 500'000;
    m.seq = map_seq;
    m.map_seq = map_seq;
    m.resolution = 0.1f;
    m.nx = 20;
    m.ny = 30;
    m.origin_x = -0.5f;
    m.origin_y = -1.5f;
    m.ncells = 600;
    m.cell_class.assign(600, traversability_map_t::CLASS_TRAVERSABLE);
    for (auto* layer : {&m.cost, &m.step_m, &m.drop_m, &m.slope_deg, &m.roughness_m, &m.span_m, &m.certainty})
        layer->assign(600, 0.0f);
    return m;
}

candidate_arcs_t arcs_of(int64_t map_seq)
{
    candidate_arcs_t a{};
    a.utime = kUtime + map_seq * 500'000;
    a.map_seq = map_seq;
    a.length_m = 1.5f;
    a.swept_width_m = 2.2f;
    a.narcs = 3;
    a.curvature = {-0.2f, 0.0f, 0.2f};
    a.clear_distance_m = {1.5f, 0.5f, 1.5f};
    a.unknown_fraction = {0.0f, 0.0f, 0.0f};
    a.mean_cost = {0.0f, 0.0f, 0.0f};
    a.merit = {1.0f, 0.0f, 1.0f};
    a.blocked = {0, 1, 0};
    a.best = 0;
    return a;
}

void write_bytes(lcm::LogFile& log, const std::string& channel, std::vector<uint8_t> bytes)
{
    lcm::LogEvent ev{};
    ev.timestamp = kUtime;
    ev.channel = channel;
    ev.datalen = static_cast<int32_t>(bytes.size());
    ev.data = bytes.data();
    log.writeEvent(&ev);
}

int render(const test::TempDir& dir, std::vector<std::string> args, std::string& out)
{
    args.insert(args.begin(), test::bin("ugv-render"));
    const int rc = test::run(args, dir / "out.txt", dir / "err.txt", 30);
    out = test::read_file(dir / "out.txt") + test::read_file(dir / "err.txt");
    return rc;
}

// Width and height from a PNG's IHDR.
void png_size(const std::string& path, int& w, int& h)
{
    const std::string png = test::read_file(path);
    REQUIRE(png.size() > 24);
    auto be32 = [&](std::size_t at) {
        return (static_cast<uint8_t>(png[at]) << 24) | (static_cast<uint8_t>(png[at + 1]) << 16) |
               (static_cast<uint8_t>(png[at + 2]) << 8) | static_cast<uint8_t>(png[at + 3]);
    };
    w = static_cast<int>(be32(16));
    h = static_cast<int>(be32(20));
}

}  // namespace

TEST_CASE("ugv-render --traverse: pairs by map_seq, counts what does not decode, says when arcs are missing")
{
    test::TempDir dir;
    const std::string log_path = dir / "traverse.lcm";
    {
        lcm::LogFile log(log_path, "w");
        // Arcs before their map, as a daemon may publish them.
        test::write_event(log, kUtime, "ARCS", arcs_of(41));
        test::write_event(log, kUtime, "TRAVERSABILITY_MAP", map_of(41));
        write_bytes(log, "TRAVERSABILITY_MAP", {1, 2, 3, 4, 5, 6, 7, 8, 9});  // not a map
        std::vector<uint8_t> truncated = test::encoded(arcs_of(42));
        truncated.resize(truncated.size() / 2);
        write_bytes(log, "ARCS", truncated);
        // The last map's arcs are of another terrain map.
        test::write_event(log, kUtime, "TRAVERSABILITY_MAP", map_of(42));
        test::write_event(log, kUtime, "ARCS", arcs_of(43));
        test::write_event(log, kUtime, "TERRAIN_MAP", terrain_map_t{});  // another channel: not read
    }
    std::string out;
    REQUIRE(render(dir, {log_path, "--traverse", "-o", dir / "last.png"}, out) == 0);
    CHECK(out.find("2 maps read, 1 undecodable; 2 arcs read, 1 undecodable; 1 PNG written, 1 without arcs") !=
          std::string::npos);
    CHECK(out.find("1 map(s) drawn without arcs: none on ARCS of the same map_seq") != std::string::npos);
    int w = 0, h = 0;
    png_size(dir / "last.png", w, h);
    CHECK(w == 2 * 10 + 30 * 3 + 200);
    CHECK(h == 2 * 10 + 300);  // the legend is taller than this map
    // Once the arcs are required, the last map without them is a failure.
    CHECK(render(dir, {log_path, "--traverse", "--require-arcs", "-o", dir / "last.png"}, out) == 1);
    // Every map: the first with its arcs, the second without.
    REQUIRE(render(dir, {log_path, "--traverse", "--every", "1", "--cell-px", "2", "-o", dir / "each"}, out) == 0);
    CHECK(out.find("2 PNG written, 1 without arcs") != std::string::npos);
    png_size(dir / "each-00001.png", w, h);
    CHECK(w == 2 * 10 + 30 * 2 + 200);
    CHECK(std::filesystem::exists(dir / "each-00002.png"));
    CHECK_FALSE(std::filesystem::exists(dir / "each-00003.png"));
    // The arcs on another channel: none found, the map still drawn.
    REQUIRE(render(dir, {log_path, "--traverse", "--arcs-channel", "OTHER", "--every", "1", "-o", dir / "o"}, out) == 0);
    CHECK(out.find("0 arcs read") != std::string::npos);
    CHECK(out.find("2 without arcs") != std::string::npos);
}

TEST_CASE("ugv-render --traverse: a log without traversability maps is said in one line")
{
    test::TempDir dir;
    const std::string log_path = dir / "none.lcm";
    {
        lcm::LogFile log(log_path, "w");
        test::write_event(log, kUtime, "ARCS", arcs_of(1));
        write_bytes(log, "TRAVERSABILITY_MAP", {0, 0, 0});
    }
    std::string out;
    CHECK(render(dir, {log_path, "--traverse", "-o", dir / "x.png"}, out) == 1);
    CHECK(out.find("no decodable traversability map on TRAVERSABILITY_MAP in " + log_path + " (1 undecodable)") !=
          std::string::npos);
    CHECK_FALSE(std::filesystem::exists(dir / "x.png"));
}

TEST_CASE("ugv-render: options that do not go together are refused")
{
    test::TempDir dir;
    const std::string log_path = dir / "empty.lcm";
    { lcm::LogFile log(log_path, "w"); }
    std::string out;
    CHECK(render(dir, {log_path, "--traverse", "--variance"}, out) != 0);
    CHECK(out.find("excludes") != std::string::npos);
    CHECK(render(dir, {log_path, "--z-span", "1", "--z-min", "0"}, out) != 0);
    CHECK(render(dir, {log_path, "--z-span", "0"}, out) != 0);
    CHECK(render(dir, {log_path, "--require-arcs"}, out) != 0);
}
