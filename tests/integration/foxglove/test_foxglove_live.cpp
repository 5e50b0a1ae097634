// ugv-foxglove as a real process on the test's own LCM and TCP ports, seen by Foxglove's own
// client (@foxglove/ws-protocol under node, tests/foxglove/check_live.mjs) during an
// lcm-logplayer replay of the sample log: the topics and schemas of ugv-mcap's file from the
// same log, a subscription, the terrain grids decoded; two such clients at once. Exit 77
// (skipped) without node.
#include <catch2/catch.hpp>

#include <memory>
#include <vector>

#include "bridge.hpp"
#include "node_packages.hpp"
#include "sample_log.hpp"
#include "ugv_test/process.hpp"

using namespace ugv;

namespace {

constexpr int kLivePort = 18760, kLiveLcm = 7934;

}  // namespace

TEST_CASE("Foxglove's client: ugv-mcap's topics and schemas, a subscription, the terrain grids")
{
    const std::string dir_node = test::node_dir("test_foxglove_live");  // skips where node cannot be had
    test::TempDir dir;
    const std::string log = dir / "run.lcm", mcap = dir / "run.mcap";
    test::write_sample_log(log);
    REQUIRE(test::run({test::bin("ugv-mcap"), log, mcap, "--compression", "none", "--quiet"}, dir / "o", dir / "e") == 0);
    test::write_file(dir / "expected.json",
                     "{\"optional\":[\"STATUS_FOXGLOVE\",\"STATUS_FOXGLOVE/log\"],\"grid\":{\"topic\":\"TERRAIN_MAP/grid\","
                     "\"nx\":" + std::to_string(test::kMapNx) + ",\"ny\":" + std::to_string(test::kMapNy) +
                         "},\"grids\":2,\"timeout_s\":60}");
    test::Process bridge({test::bin("ugv-foxglove"), "--config", test::bridge_config(dir, kLivePort), "--lcm-url", test::lcm_url(kLiveLcm)},
                         dir / "bridge.out", dir / "bridge.err");
    REQUIRE(test::wait_serving(bridge));
    // Two clients at once, each with its own subscription.
    std::vector<std::unique_ptr<test::Process>> checks;
    for (const char* name : {"check1.out", "check2.out"})
        checks.push_back(std::make_unique<test::Process>(
            std::vector<std::string>{test::which("node"), dir_node + "/check_live.mjs",
                                     "ws://127.0.0.1:" + std::to_string(kLivePort), mcap, dir / "expected.json"},
            dir / name, dir / name));
    const auto any_running = [&] {
        for (auto& c : checks)
            if (c->running()) return true;
        return false;
    };
    // The log replayed until the clients are done (their topics come with the replay's first messages).
    for (int replays = 0; any_running() && replays < 40; ++replays)
        test::run({"/usr/bin/lcm-logplayer", "--lcm-url=" + test::lcm_url(kLiveLcm), "--speed=4", log}, dir / "p", dir / "p",
                  30);
    for (auto& check : checks) {
        const int rc = check->wait_exit(60);
        INFO(check->out());
        INFO(bridge.err());
        CHECK(rc == 0);
        std::printf("%s", check->out().c_str());
    }
    bridge.signal(SIGTERM);
    CHECK(bridge.wait_exit(10) == 0);
}

