// The map survives a restart (issue 23): ugv-terrain saves its map (map_file, every
// map_save_period_s and on SIGTERM); killed with SIGKILL and started again at the same pose,
// its first map holds the known cells again; started 100 m away, or from a truncated or
// foreign file, it starts empty, says so in one line, and runs. Real daemon, LCM port 7746.
#include <catch2/catch.hpp>

#include <csignal>
#include <filesystem>
#include <string>

#include <ugv/terrain_map_t.hpp>

#include "status_rig.hpp"
#include "terrain_feed.hpp"

using namespace ugv;
using namespace ugv::test;
using namespace ugv::test::status;

namespace {

constexpr int kPort = 7746;

struct Terrain
{
    TempDir& dir;
    std::string name;
    Listener l{lcm_url(kPort), "STATUS_TERRAIN"};
    std::vector<int> known;  // known cells of each map received
    std::unique_ptr<Process> p;

    Terrain(TempDir& d, const std::string& n) : dir(d), name(n)
    {
        bus::subscribe<terrain_map_t>(l.bus(), "TERRAIN_MAP", [this](const std::string&, const terrain_map_t& m, int64_t) {
            known.push_back(known_cells(m));
        });
        write_file(dir / "terrain.toml", small_map_config() + "map_file = \"" + dir / "map.bin" +
                                             "\"\nmap_save_period_s = 1.0\n");
        p = std::make_unique<Process>(std::vector<std::string>{bin("ugv-terrain"), "--config", dir / "terrain.toml",
                                                               "--lcm-url", lcm_url(kPort)},
                                      dir / (name + ".out"), dir / (name + ".err"));
        REQUIRE(l.until([&] { return !l.states.empty(); }, 10.0));
    }
    std::string err() const { return read_file(dir / (name + ".err")); }
};

}  // namespace

TEST_CASE("ugv-terrain: killed with SIGKILL, restarted, the map comes back; moved or corrupt, it starts empty",
          "[terrain][restart]")
{
    TempDir dir;
    TerrainFeed feed;
    Every pose_every(100'000), cloud_every(100'000);
    int saved_known = 0;
    {
        Terrain t(dir, "first");
        INFO(t.err());
        const auto both = [&] {
            pose_every([&] { feed.pose(t.l.bus()); });
            cloud_every([&] { feed.cloud(t.l.bus()); });
        };
        REQUIRE(t.l.until([&] { return !t.known.empty() && t.known.back() > 500; }, 20.0, both));
        // Points stop; the map stays as it is while the poses go on, and the next save (every
        // second while it changes) writes it.
        const auto pose_only = [&] { pose_every([&] { feed.pose(t.l.bus()); }); };
        t.l.for_seconds(3.0, pose_only);
        CHECK(t.l.counter("map_saves") > 0);
        CHECK(t.l.counter("map_save_failures") == 0);
        t.known.clear();
        REQUIRE(t.l.until([&] { return t.known.size() >= 2; }, 5.0, pose_only));
        saved_known = t.known.back();
        CHECK(t.known.front() == saved_known);
        t.p->signal(SIGKILL);
        t.p->wait_exit(5.0);
    }
    REQUIRE(std::filesystem::exists(dir / "map.bin"));
    CHECK_FALSE(std::filesystem::exists(dir / "map.bin.tmp"));
    std::filesystem::copy_file(dir / "map.bin", dir / "good.bin");
    std::printf("terrain restart: %d known cells before SIGKILL, map file %ju bytes\n", saved_known,
                static_cast<uintmax_t>(std::filesystem::file_size(dir / "map.bin")));

    SECTION("same pose: the first map has every known cell back")
    {
        Terrain t(dir, "same");
        INFO(t.err());
        REQUIRE(t.l.until([&] { return !t.known.empty(); }, 10.0, [&] { pose_every([&] { feed.pose(t.l.bus()); }); }));
        std::printf("terrain restart: %d known cells in the first map after the restart\n", t.known.front());
        CHECK(t.known.front() == saved_known);
        const std::string restored = "map restored: " + std::to_string(saved_known) + " known cells";
        CHECK(wait_until([&] { return t.err().find(restored) != std::string::npos; }, 5.0));
        t.l.for_seconds(1.5, [&] { pose_every([&] { feed.pose(t.l.bus()); }); });
        CHECK(t.l.counter("cells_restored") == saved_known);
        t.p->signal(SIGTERM);
        CHECK(t.p->wait_exit(5.0) == 0);
    }
    SECTION("100 m away (more than the map's 10 m extent): it starts empty")
    {
        Terrain t(dir, "moved");
        INFO(t.err());
        feed.east_m = 100.0;
        REQUIRE(t.l.until([&] { return !t.known.empty(); }, 10.0, [&] { pose_every([&] { feed.pose(t.l.bus()); }); }));
        CHECK(t.known.front() == 0);
        const std::string dropped = "saved map dropped: the first pose is 100.0 m from it";
        CHECK(wait_until([&] { return t.err().find(dropped) != std::string::npos; }, 5.0));
        CHECK(t.p->running());
    }
    SECTION("a truncated, a damaged and a foreign file: refused in one line, starts empty, runs")
    {
        const std::string good = read_file(dir / "good.bin");
        std::string damaged = good;
        damaged[damaged.size() / 2] = static_cast<char>(damaged[damaged.size() / 2] ^ 0x10);
        const std::vector<std::pair<std::string, std::string>> cases = {
            {"truncated", good.substr(0, good.size() / 2)},
            {"damaged", damaged},
            {"foreign", std::string(4096, 'x')},
        };
        for (const auto& [what, bytes] : cases) {
            write_file(dir / "map.bin", bytes);
            Terrain t(dir, what);
            INFO(what << ": " << t.err());
            REQUIRE(t.l.until([&] { return !t.known.empty(); }, 10.0, [&] { pose_every([&] { feed.pose(t.l.bus()); }); }));
            CHECK(t.known.front() == 0);
            const std::string err = t.err();
            const auto refused = err.find("refused");
            CHECK(refused != std::string::npos);
            CHECK(err.find("refused", refused + 1) == std::string::npos);
            CHECK(t.p->running());
            t.p->signal(SIGTERM);
            CHECK(t.p->wait_exit(5.0) == 0);
        }
    }
}
