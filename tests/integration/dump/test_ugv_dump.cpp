// ugv-dump on a log written by lcm-logger itself, and on the live bus.
#include <catch2/catch.hpp>

#include <sstream>

#include "ugv_test/process.hpp"
#include "ugv_test/sample_messages.hpp"

using namespace ugv;

namespace {
std::vector<std::string> lines_of(const std::string& s)
{
    std::vector<std::string> out;
    std::istringstream in(s);
    for (std::string l; std::getline(in, l);) out.push_back(l);
    return out;
}
}  // namespace

TEST_CASE("ugv-dump prints every message of an lcm-logger log as JSON lines")
{
    test::TempDir dir;
    const std::string url = test::lcm_url(7621);
    const std::string log = dir / "run.lcm";
    std::vector<std::string> names;
    {
        test::Process logger({"/usr/bin/lcm-logger", "--lcm-url=" + url, "-f", log}, dir / "lo", dir / "le");
        REQUIRE(test::wait_until([&] { return std::filesystem::exists(log); }, 10));
        auto b = bus::open_live(url);
        // lcm-logger subscribes after creating the file: publish until the first arrives.
        REQUIRE(test::wait_until(
            [&] {
                laser_scan_t probe{};
                bus::publish(*b, "PROBE", probe);
                return std::filesystem::file_size(log) > 0;
            },
            10));
        names = test::publish_samples(*b);
        // lcm-logger flushes on its own schedule: give it time, then stop it (SIGINT flushes).
        usleep(500'000);
        logger.signal(SIGINT);
        REQUIRE(logger.wait_exit(5) == 0);
    }
    REQUIRE(test::run({test::bin("ugv-dump"), "--log", log, "--channel", "SAMPLE_.*"}, dir / "o", dir / "e") == 0);
    const auto lines = lines_of(test::read_file(dir / "o"));
    REQUIRE(lines.size() == 14);
    for (std::size_t k = 0; k < 14; ++k) {
        INFO(lines[k]);
        CHECK(lines[k].rfind("{\"channel\":\"SAMPLE_" + names[k] + "\",\"utime\":" + std::to_string(1000 + k) +
                                 ",\"recv_utime\":",
                             0) == 0);
        CHECK(lines[k].find(",\"type\":\"ugv." + names[k] + "\",\"fields\":{\"utime\":") != std::string::npos);
    }
    CHECK(lines[6].find("\"position\":[12.5,0,0]") != std::string::npos);

    REQUIRE(test::run({test::bin("ugv-dump"), "--log", log, "--channel", "SAMPLE_.*", "--count", "3"}, dir / "o", dir / "e") == 0);
    CHECK(lines_of(test::read_file(dir / "o")).size() == 3);
    CHECK(test::run({test::bin("ugv-dump"), "--log", log, "--channel", "SAMPLE_pose_t", "--count", "2"}, dir / "o",
                    dir / "e") == 1);
    CHECK(test::read_file(dir / "e") == "ugv-dump: 1 of 2 messages in the log\n");
    CHECK(test::run({test::bin("ugv-dump"), "--log", log, "--channel", "(["}, dir / "o", dir / "e") == 2);
}

TEST_CASE("ugv-dump on the live bus: --count ends it, --timeout gives exit 1 when too few came")
{
    test::TempDir dir;
    const std::string url = test::lcm_url(7622);
    test::Process dump({test::bin("ugv-dump"), "--lcm-url", url, "--channel", "SAMPLE_imu_t", "--count", "2", "--timeout", "30"},
                       dir / "o", dir / "e");
    auto b = bus::open_live(url);
    // Keep publishing until it has what it wants (it may start listening after our first).
    REQUIRE(test::wait_until(
        [&] {
            test::publish_samples(*b);
            usleep(50'000);
            return !dump.running();
        },
        20));
    CHECK(dump.wait_exit(1) == 0);
    const auto lines = lines_of(dump.out());
    REQUIRE(lines.size() == 2);
    CHECK(lines[0].find("\"type\":\"ugv.imu_t\"") != std::string::npos);
    CHECK(lines[0].find("\"yaw\":1.5") != std::string::npos);

    const int code = test::run({test::bin("ugv-dump"), "--lcm-url", test::lcm_url(7623), "--count", "1", "--timeout", "0.3"},
                               dir / "o", dir / "e");
    CHECK(code == 1);
    CHECK(test::read_file(dir / "e") == "ugv-dump: 0 of 1 messages before the timeout\n");
}
