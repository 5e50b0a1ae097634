// ugv-traverse end to end, on terrain maps of a known world: flat ground and a box 0.6 m
// tall (0.6 m x 0.4 m) straight ahead that the vehicle drives towards (0.4 m per map). The
// maps are played into a live daemon with lcm-logplayer, replayed with --replay, and sent
// malformed or absurdly stamped; bad config keys are refused.
#include <catch2/catch.hpp>

#include <lcm/lcm-cpp.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <map>
#include <string>
#include <vector>

#include <ugv/candidate_arcs_t.hpp>
#include <ugv/daemon_status_t.hpp>
#include <ugv/terrain_map_t.hpp>
#include <ugv/traversability_map_t.hpp>

#include "ugv/bus/typed.hpp"
#include "ugv/io/clock.hpp"
#include "ugv_test/process.hpp"

using namespace ugv;

namespace {

// The world: 100 x 100 cells of 0.2 m, the map's first row at the rear bumper (x = -0.5);
// the box covers rows box_row(k) .. +2 and columns 49..50 (y -0.2 .. 0.2) in map k: every
// one of its cells borders the ground.
constexpr int kN = 100;
constexpr double kRes = 0.2, kOriginX = -0.5, kOriginY = -10.0;
constexpr int kMaps = 10;
constexpr int64_t kPeriodUs = 500'000;
constexpr double kBoxHeight = 0.6;
constexpr double kFrontX = 2.0, kMargin = 0.3;  // the daemon's defaults (footprint, arcs)

int box_row(int k) { return 43 - 2 * k; }
bool in_box(int k, int i, int j) { return i >= box_row(k) && i < box_row(k) + 3 && j >= 49 && j <= 50; }
double box_face_x(int k) { return kOriginX + box_row(k) * kRes; }

terrain_map_t world_map(int k, int64_t utime)
{
    terrain_map_t m{};
    m.utime = utime;
    m.seq = k;
    m.pose.utime = utime;
    m.pose.position[0] = 0.4 * k;
    m.pose.orientation[0] = 1.0;
    m.pose.status = pose_t::STATUS_OK;
    m.resolution = static_cast<float>(kRes);
    m.nx = kN;
    m.ny = kN;
    m.origin_x = static_cast<float>(kOriginX);
    m.origin_y = static_cast<float>(kOriginY);
    m.ncells = kN * kN;
    m.mean_z.assign(kN * kN, 0.0f);
    m.variance_z.assign(kN * kN, 1e-4f);
    m.count.assign(kN * kN, 5);
    m.max_z.assign(kN * kN, 0.02f);
    m.min_z.assign(kN * kN, -0.02f);
    m.age_s.assign(kN * kN, 0.0f);  // fresh
    for (int i = 0; i < kN; ++i)
        for (int j = 0; j < kN; ++j) {
            if (!in_box(k, i, j)) continue;
            const std::size_t c = static_cast<std::size_t>(i * kN + j);
            m.mean_z[c] = static_cast<float>(kBoxHeight);
            m.max_z[c] = static_cast<float>(kBoxHeight + 0.02);
            m.min_z[c] = static_cast<float>(kBoxHeight - 0.02);
        }
    return m;
}

// The kMaps maps as an lcm-logger log, stamped from t0 on (event time = map time).
void write_world_log(const std::string& path, int64_t t0)
{
    int64_t now = t0;
    auto w = bus::open_log_writer(path, [&] { return now; });
    for (int k = 0; k < kMaps; ++k) {
        now = t0 + k * kPeriodUs;
        bus::publish(*w, "TERRAIN_MAP", world_map(k, now));
    }
}

template <class T>
std::vector<T> decode_all(const std::string& path, const std::string& channel)
{
    std::vector<T> out;
    lcm::LogFile log(path, "r");
    REQUIRE(log.good());
    while (const lcm::LogEvent* ev = log.readNextEvent()) {
        if (ev->channel != channel) continue;
        T m;
        REQUIRE(m.decode(ev->data, 0, ev->datalen) == ev->datalen);
        out.push_back(std::move(m));
    }
    return out;
}

std::vector<uint8_t> bytes_of(candidate_arcs_t m)
{
    m.seq = 0;  // the arcs themselves, whichever maps came before
    std::vector<uint8_t> b(static_cast<std::size_t>(m.getEncodedSize()));
    m.encode(b.data(), 0, static_cast<int>(b.size()));
    return b;
}

// What the daemon published, received live.
struct Listener
{
    std::unique_ptr<bus::Bus> bus;
    std::map<int64_t, candidate_arcs_t> arcs;  // by map_seq
    std::map<int64_t, traversability_map_t> maps;
    std::vector<daemon_status_t> status;

    explicit Listener(const std::string& url) : bus(bus::open_live(url))
    {
        bus::subscribe<candidate_arcs_t>(*bus, "ARCS", [this](const std::string&, const candidate_arcs_t& m, int64_t) {
            arcs[m.map_seq] = m;
        });
        bus::subscribe<traversability_map_t>(*bus, "TRAVERSABILITY_MAP",
                                             [this](const std::string&, const traversability_map_t& m, int64_t) {
                                                 maps[m.map_seq] = m;
                                             });
        bus::subscribe<daemon_status_t>(*bus, "STATUS_TRAVERSE", [this](const std::string&, const daemon_status_t& m,
                                                                         int64_t) { status.push_back(m); });
    }
    bool spin_until(const std::function<bool()>& done, double timeout_s)
    {
        return test::wait_until([&] { bus->handle(20); return done(); }, timeout_s);
    }
    int64_t counter(const std::string& name) const
    {
        if (status.empty()) return -1;
        const daemon_status_t& s = status.back();
        for (std::size_t k = 0; k < s.counter_names.size(); ++k)
            if (s.counter_names[k] == name) return s.counter_values[k];
        return -1;
    }
};

// A live ugv-traverse on its own port, subscribed before this returns (its STATUS came).
struct LiveTraverse
{
    test::TempDir dir;
    std::string url;
    Listener listener;
    std::unique_ptr<test::Process> process;

    LiveTraverse(int port, const std::string& config)
        : url(test::lcm_url(port) + "&recv_buf_size=4194304"), listener(url)
    {
        test::write_file(dir / "traverse.toml", config);
        process = std::make_unique<test::Process>(
            std::vector<std::string>{test::bin("ugv-traverse"), "--config", dir / "traverse.toml", "--lcm-url", url},
            dir / "out", dir / "err");
        INFO(test::read_file(dir / "err"));
        REQUIRE(listener.spin_until([&] { return !listener.status.empty(); }, 10));
    }
    std::string err() const { return test::read_file(dir / "err"); }
};

// Plays log at speed into port; all kMaps analysed maps received (or the timeout).
std::map<int64_t, candidate_arcs_t> play(const std::string& log, const std::string& speed, LiveTraverse& t)
{
    test::TempDir d;
    const int rc = test::run({"/usr/bin/lcm-logplayer", "-s", speed, "-l", t.url, log}, d / "o", d / "e", 30.0);
    REQUIRE(rc == 0);
    t.listener.spin_until([&] { return t.listener.arcs.size() >= static_cast<std::size_t>(kMaps); }, 5);
    INFO(t.err());
    REQUIRE(t.listener.arcs.size() >= static_cast<std::size_t>(kMaps) - 2);  // loopback loss: rare, tolerated
    return t.listener.arcs;
}

// The map-time stamps of a played log are in the past or, faster than 1x, in the future.
const std::string kLiveConfig = "max_stamp_ahead_s = 60.0\n";

}  // namespace

TEST_CASE("ugv-traverse on a played log: the box is an obstacle, the straight arc stops at it, side arcs are free; "
          "the same arcs at 1x and 4x")
{
    test::TempDir dir;
    const std::string log = dir / "maps.lcm";
    write_world_log(log, io::now_utime() + 300'000);

    LiveTraverse slow(7764, kLiveConfig);
    const auto at_1x = play(log, "1", slow);
    LiveTraverse fast(7765, kLiveConfig);
    const auto at_4x = play(log, "4", fast);

    // The arcs do not depend on the playing speed.
    int compared = 0;
    for (const auto& [map_seq, arcs] : at_1x) {
        const auto other = at_4x.find(map_seq);
        if (other == at_4x.end()) continue;
        INFO("map_seq " << map_seq);
        CHECK(bytes_of(arcs) == bytes_of(other->second));
        ++compared;
    }
    CHECK(compared >= kMaps - 2);

    for (const auto& [k64, a] : at_1x) {
        const int k = static_cast<int>(k64);
        INFO("map " << k);
        REQUIRE(a.narcs == 25);
        CHECK(a.map_seq == k);
        CHECK(a.utime == a.pose.utime);  // the map's time and pose, copied together
        CHECK(a.pose.position[0] == Approx(0.4 * k));
        const int straight = a.narcs / 2;
        CHECK(a.curvature[static_cast<std::size_t>(straight)] == Approx(0.0f).margin(1e-6));
        // Straight ahead: blocked where the footprint (front bumper, widened by the margin)
        // meets the box's near face, within a cell either way.
        CHECK(a.blocked[static_cast<std::size_t>(straight)] == 1);
        const double clear = a.clear_distance_m[static_cast<std::size_t>(straight)];
        CHECK(clear >= box_face_x(k) - kFrontX - kMargin - 2 * kRes);
        CHECK(clear <= box_face_x(k) - kFrontX + 2 * kRes);
        // The tightest turns either way pass beside it.
        CHECK(a.blocked.front() == 0);
        CHECK(a.blocked.back() == 0);
        CHECK(a.clear_distance_m.front() == Approx(a.length_m));
        CHECK(a.best >= 0);
        CHECK(a.best != straight);
    }

    // The traversability map of the last map received: the box OBSTACLE, flat ground
    // (a metre or more from the box and from the map's edges) TRAVERSABLE.
    REQUIRE(!slow.listener.maps.empty());
    const traversability_map_t& t = slow.listener.maps.rbegin()->second;
    const int k = static_cast<int>(t.map_seq);
    REQUIRE(t.ncells == kN * kN);
    CHECK(t.nx == kN);
    CHECK(t.origin_x == Approx(kOriginX));
    CHECK(t.pose.position[0] == Approx(0.4 * k));
    int box_cells = 0, box_obstacles = 0, flat_cells = 0, flat_traversable = 0;
    for (int i = 5; i < kN - 5; ++i)
        for (int j = 5; j < kN - 5; ++j) {
            const int8_t c = t.cell_class[static_cast<std::size_t>(i * kN + j)];
            if (in_box(k, i, j)) {
                ++box_cells;
                box_obstacles += c == traversability_map_t::CLASS_OBSTACLE ? 1 : 0;
            } else if (i < box_row(k) - 5 || i >= box_row(k) + 10 || j < 43 || j > 56) {
                ++flat_cells;
                flat_traversable += c == traversability_map_t::CLASS_TRAVERSABLE ? 1 : 0;
            }
        }
    CHECK(box_cells == 6);
    CHECK(box_obstacles == box_cells);
    CHECK(flat_traversable == flat_cells);
    CHECK(slow.listener.spin_until([&] { return slow.listener.counter("maps_published") == static_cast<int64_t>(at_1x.size()); }, 3));
    CHECK(slow.listener.counter("maps_malformed") == 0);
}

TEST_CASE("ugv-traverse --replay LOG --out LOG gives the same bytes twice")
{
    test::TempDir dir;
    const std::string log = dir / "maps.lcm";
    write_world_log(log, 1'700'000'000'000'000);
    for (const char* out : {"out1.lcm", "out2.lcm"}) {
        const int rc = test::run({test::bin("ugv-traverse"), "--replay", log, "--out", dir / out}, dir / "o", dir / "e", 30.0);
        INFO(test::read_file(dir / "e"));
        REQUIRE(rc == 0);
    }
    for (const char* channel : {"ARCS", "TRAVERSABILITY_MAP"}) {
        INFO(channel);
        std::vector<std::vector<uint8_t>> runs[2];
        int r = 0;
        for (const char* out : {"out1.lcm", "out2.lcm"}) {
            lcm::LogFile f(dir / out, "r");
            REQUIRE(f.good());
            while (const lcm::LogEvent* ev = f.readNextEvent()) {
                if (ev->channel != channel) continue;
                const auto* p = static_cast<const uint8_t*>(ev->data);
                runs[r].emplace_back(p, p + ev->datalen);
            }
            ++r;
        }
        CHECK(runs[0].size() == static_cast<std::size_t>(kMaps));
        CHECK(runs[0] == runs[1]);
    }
    const auto arcs = decode_all<candidate_arcs_t>(dir / "out1.lcm", "ARCS");
    REQUIRE(arcs.size() == static_cast<std::size_t>(kMaps));
    for (int k = 0; k < kMaps; ++k) {
        CHECK(arcs[static_cast<std::size_t>(k)].seq == k);
        CHECK(arcs[static_cast<std::size_t>(k)].map_seq == k);
    }
}

TEST_CASE("ugv-traverse counts and drops malformed and NaN maps, refuses absurd stamps, and goes on")
{
    LiveTraverse t(7766, kLiveConfig);
    auto out = bus::open_live(t.url);
    int64_t seq = 0;
    const auto send = [&](terrain_map_t m) {
        m.seq = seq++;
        m.utime = m.pose.utime = io::now_utime();
        bus::publish(*out, "TERRAIN_MAP", m);
        usleep(100'000);  // one at a time, in order
    };
    send(world_map(0, 0));
    // Refused for their stamps before the analysis sees them.
    const auto send_stamped = [&](int64_t utime) {
        terrain_map_t m = world_map(0, 0);
        m.seq = seq++;
        m.utime = m.pose.utime = utime;
        bus::publish(*out, "TERRAIN_MAP", m);
        usleep(100'000);
    };
    send_stamped(INT64_MAX);
    send_stamped(io::now_utime() - 3'600'000'000);  // an hour old: beyond max_age_s
    terrain_map_t m = world_map(0, 0);
    m.nx = kN - 1;  // ncells (and every array) disagree with nx * ny
    send(m);
    m = world_map(0, 0);
    m.resolution = NAN;
    send(m);
    m = world_map(0, 0);
    m.max_z[5000] = NAN;  // in a known cell (count 5, a mean); a NaN mean is an unknown cell
    send(m);
    m = world_map(0, 0);
    m.max_z[5000] = -1.0f;  // below its min
    send(m);
    send(world_map(1, 0));
    REQUIRE(t.listener.spin_until([&] { return t.listener.counter("maps_in") == 6; }, 5));
    CHECK(t.listener.counter("maps_malformed") == 4);
    CHECK(t.listener.counter("stamps_ahead") == 1);
    CHECK(t.listener.counter("stamps_too_old") == 1);
    CHECK(t.listener.counter("maps_published") == 2);
    CHECK(t.listener.arcs.size() == 2);
    CHECK(t.listener.arcs.count(7) == 1);  // the map after the bad ones
    CHECK(t.process->running());
    // One rate-limited line for the four, naming the first one's fault.
    const std::string err = t.err();
    INFO(err);
    std::size_t lines = 0;
    for (std::size_t p = err.find("dropped:"); p != std::string::npos; p = err.find("dropped:", p + 1)) ++lines;
    CHECK(lines == 1);
    CHECK(err.find("map seq 3 dropped") != std::string::npos);
}

TEST_CASE("ugv-traverse refuses a bad key with one line naming it and exit status 2")
{
    const std::vector<std::pair<std::string, std::string>> cases = {
        {"[arcs]\nunknown_policy = \"reckless\"\n", "arcs.unknown_policy"},
        {"[arcs]\ncount = 0\n", "arcs.count"},
        {"[classifier]\nmax_step_m = -0.1\n", "classifier.max_step_m"},
        {"[classifier]\nmax_age_s = nan\n", "classifier.max_age_s"},
        {"[classifier]\nshadow_radius_m = 0.0\n", "classifier.shadow_radius_m"},
        {"[footprint]\nwidth_m = 0.0\n", "footprint.width_m"},
        {"arcs_channel = \"A R C S\"\n", "arcs_channel"},
        {"max_stamp_ahead_s = -1.0\n", "max_stamp_ahead_s"},
        {"[arcs]\nlenght_m = 10.0\n", "arcs.lenght_m"},
        {"[arcs]\nmax_curvature_per_m = 1.0\n", "arcs.max_curvature_per_m"},  // radius 1 m < 0.8 + 0.3
    };
    for (const auto& [text, key] : cases) {
        test::TempDir dir;
        test::write_file(dir / "traverse.toml", text);
        const int rc = test::run({test::bin("ugv-traverse"), "--config", dir / "traverse.toml", "--print-config"},
                                 dir / "o", dir / "e", 10.0);
        const std::string err = test::read_file(dir / "e");
        INFO(text << " -> " << err);
        CHECK(rc == 2);
        CHECK(err.find(": " + key + ": ") != std::string::npos);
        CHECK(std::count(err.begin(), err.end(), '\n') == 1);
    }
}

TEST_CASE("ugv-traverse is RUNNING while ARCS flow, DEGRADED saying why while every map is dropped")
{
    LiveTraverse t(7767, kLiveConfig + "health_timeout_s = 1.0\n");
    auto out = bus::open_live(t.url);
    int64_t seq = 0;
    // Sends a map every 0.25 s until the daemon's STATUS says `state`, its last_error holding
    // `why` (or 8 s pass).
    const auto feed_until = [&](bool malformed, int8_t state, const std::string& why) {
        return test::wait_until(
            [&] {
                terrain_map_t m = world_map(0, 0);
                if (malformed) m.max_z[100] = -1.0f;
                m.seq = seq++;
                m.utime = m.pose.utime = io::now_utime();
                bus::publish(*out, "TERRAIN_MAP", m);
                t.listener.spin_until([] { return false; }, 0.25);
                if (t.listener.status.empty()) return false;
                const daemon_status_t& s = t.listener.status.back();
                return s.state == state && s.last_error.find(why) != std::string::npos;
            },
            8);
    };
    REQUIRE(feed_until(false, daemon_status_t::STATE_RUNNING, ""));
    // The generic "no ARCS for 1.0 s" may come first; the library's reason follows.
    CHECK(feed_until(true, daemon_status_t::STATE_DEGRADED, "no map analysed for"));
    INFO(t.listener.status.back().last_error);
    CHECK(t.listener.status.back().last_error.find("max below min") != std::string::npos);
    CHECK(feed_until(false, daemon_status_t::STATE_RUNNING, ""));
    CHECK(t.process->running());
}

TEST_CASE("ugv-traverse takes each cell's age from the map: data older than max_age_s is UNKNOWN")
{
    test::TempDir dir;
    const std::string log = dir / "old.lcm";
    {
        const int64_t t0 = 1'700'000'000'000'000;
        int64_t now = t0;
        auto w = bus::open_log_writer(log, [&] { return now; });
        terrain_map_t m = world_map(0, t0);
        m.age_s.assign(static_cast<std::size_t>(m.ncells), 1.0f);
        for (int i = 0; i < kN; ++i)
            for (int j = 0; j < kN; ++j)
                if (in_box(0, i, j)) m.age_s[static_cast<std::size_t>(i * kN + j)] = 120.0f;  // > max_age_s 60
        bus::publish(*w, "TERRAIN_MAP", m);
    }
    const int rc = test::run({test::bin("ugv-traverse"), "--replay", log, "--out", dir / "out.lcm"}, dir / "o", dir / "e", 30.0);
    INFO(test::read_file(dir / "e"));
    REQUIRE(rc == 0);
    const auto maps = decode_all<traversability_map_t>(dir / "out.lcm", "TRAVERSABILITY_MAP");
    REQUIRE(maps.size() == 1);
    int box_unknown = 0;
    for (int i = 0; i < kN; ++i)
        for (int j = 0; j < kN; ++j)
            if (in_box(0, i, j))
                box_unknown += maps[0].cell_class[static_cast<std::size_t>(i * kN + j)] == traversability_map_t::CLASS_UNKNOWN;
    CHECK(box_unknown == 6);
    CHECK(maps[0].cell_class[static_cast<std::size_t>(20 * kN + 20)] == traversability_map_t::CLASS_TRAVERSABLE);
    const auto arcs = decode_all<candidate_arcs_t>(dir / "out.lcm", "ARCS");
    REQUIRE(arcs.size() == 1);
    CHECK(arcs[0].blocked[static_cast<std::size_t>(arcs[0].narcs / 2)] == 0);  // the box forgotten (optimistic)
}
