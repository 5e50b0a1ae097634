// ugv-foxglove's failure modes at start-up: each a line naming the cause, exit 2.
#include <catch2/catch.hpp>

#include "bridge.hpp"
#include "ugv_test/process.hpp"

using namespace ugv;

namespace {

constexpr int kPort = 18763, kLcm = 7937;

}  // namespace

TEST_CASE("a bad key: FILE: KEY: why, exit 2")
{
    test::TempDir dir;
    for (const auto& [line, key] : {std::pair{"address = \"vehicle\"", "address"}, std::pair{"port = 0", "port"},
                                    std::pair{"no_raw = \"(\"", "no_raw"}, std::pair{"client_queue_kb = 1", "client_queue_kb"}}) {
        INFO(line);
        const std::string cfg = dir / "bad.toml";
        test::write_file(cfg, std::string(line) + "\n");
        const int rc = test::run({test::bin("ugv-foxglove"), "--config", cfg, "--lcm-url", test::lcm_url(kLcm)}, dir / "o",
                                 dir / "e", 20);
        CHECK(rc == 2);
        CHECK(test::read_file(dir / "e").find(key) != std::string::npos);
    }
}

TEST_CASE("the port taken: ADDRESS:PORT: cannot listen, exit 2")
{
    test::TempDir dir;
    test::Process first({test::bin("ugv-foxglove"), "--config", test::bridge_config(dir, kPort), "--lcm-url", test::lcm_url(kLcm)},
                        dir / "o1", dir / "e1");
    REQUIRE(test::wait_serving(first));
    const int rc = test::run({test::bin("ugv-foxglove"), "--config", dir / "foxglove.toml", "--lcm-url", test::lcm_url(kLcm)},
                             dir / "o2", dir / "e2", 20);
    CHECK(rc == 2);
    CHECK(test::read_file(dir / "e2").find("127.0.0.1:" + std::to_string(kPort) + ": cannot listen") != std::string::npos);
    first.signal(SIGTERM);
    CHECK(first.wait_exit(10) == 0);
}

TEST_CASE("--version")
{
    test::TempDir dir;
    CHECK(test::run({test::bin("ugv-foxglove"), "--version"}, dir / "o", dir / "e", 20) == 0);
    CHECK(test::read_file(dir / "o").rfind("ugv-foxglove ", 0) == 0);
}
