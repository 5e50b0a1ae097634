// Every counter of every library a daemon runs appears in its STATUS message, from the first
// message on: the counter structs name their fields once (visit) and the daemons publish
// them generically, so a counter added to a library cannot be left unpublished.
#include <catch2/catch.hpp>

#include <algorithm>
#include <set>

#include "foxglove_node.hpp"
#include "gps_node.hpp"
#include "nodscan_node.hpp"
#include "servo_node.hpp"
#include "terrain_node.hpp"
#include "traverse_node.hpp"
#include "ugv/bus/typed.hpp"
#include "ugv/daemon_status_t.hpp"
#include "ugv/estimation/pose_estimator.hpp"
#include "ugv/microstrain_gx1/session.hpp"
#include "ugv/novatel/session.hpp"
#include "ugv/runtime/counters.hpp"
#include "ugv/runtime/host_clock.hpp"
#include "ugv/runtime/stamp_gate.hpp"
#include "ugv/sick_lms2xx/session.hpp"
#include "ugv_test/process.hpp"

using namespace ugv;

namespace {

struct Case
{
    std::string program, status_channel, config;
    std::vector<std::string> library_counters;
    int lcm_port = 0;  // 0: the next port of the block from 7660
};

template <class... S>
std::vector<std::string> names_of(const S&... structs)
{
    std::vector<std::string> all;
    (
        [&] {
            const auto names = runtime::counter_names(structs);
            all.insert(all.end(), names.begin(), names.end());
        }(),
        ...);
    return all;
}

// The first STATUS message of the daemon, started on its own port with the config given.
daemon_status_t first_status(const Case& c, int port)
{
    test::TempDir dir;
    test::write_file(dir / "config.toml", c.config);
    const std::string url = test::lcm_url(port);
    auto listen = bus::open_live(url);
    std::vector<daemon_status_t> status;
    bus::subscribe<daemon_status_t>(*listen, c.status_channel,
                                    [&](const std::string&, const daemon_status_t& m, int64_t) { status.push_back(m); });
    test::Process d({test::bin(c.program), "--config", dir / "config.toml", "--lcm-url", url}, dir / "out", dir / "err");
    const bool got = test::wait_until([&] { listen->handle(20); return !status.empty(); }, 10);
    INFO(c.program << " stderr: " << test::read_file(dir / "err"));
    REQUIRE(got);
    return status.front();
}

}  // namespace

TEST_CASE("status: every library counter of every daemon is in its first STATUS message")
{
    const std::string nowhere = "/nonexistent/ugv-status-test";
    const std::vector<Case> cases = {
        {"ugv-gps", "STATUS_GPS", "device = \"" + nowhere + "\"\n",
         names_of(novatel::SplitterCounters{}, novatel::DecoderCounters{}, novatel::SessionCounters{})},
        {"ugv-lms", "STATUS_LMS", "device = \"" + nowhere + "\"\n", names_of(sick_lms2xx::SessionStats{})},
        {"ugv-imu", "STATUS_IMU", "device = \"" + nowhere + "\"\n",
         names_of(microstrain_gx1::ParserCounters{}, microstrain_gx1::SessionCounters{})},
        {"ugv-servo", "STATUS_SERVO", "transport = \"slcan:" + nowhere + "\"\n",
         names_of(canopen::DriveCounters{}, servo_daemon::ServoNodeCounters{})},
        {"ugv-nodscan", "STATUS_NODSCAN", "", names_of(nodscan_daemon::NodscanCounters{}, runtime::StampCounters{})},
        {"ugv-pose", "STATUS_POSE", "", names_of(estimation::EstimatorCounters{}, runtime::StampCounters{})},
        {"ugv-terrain", "STATUS_TERRAIN", "",
         names_of(terrain::MapCounters{}, terrain_daemon::NodeCounters{}, runtime::StampCounters{})},
        // 7667 is the stack's default port: ugv-traverse has one of its own tests' block.
        {"ugv-traverse", "STATUS_TRAVERSE", "",
         names_of(traverse::TraverseCounters{}, traverse_daemon::NodeCounters{}, runtime::StampCounters{}), 7776},
        // Its WebSocket port too is one of its own (TCP 18800).
        {"ugv-foxglove", "STATUS_FOXGLOVE", "address = \"127.0.0.1\"\nport = 18800\n",
         names_of(foxglove_daemon::NodeCounters{}, foxglove_daemon::ServerCounters{}, foxglove::ConverterCounters{}), 7685},
    };
    int port = 7660;
    for (const Case& c : cases) {
        SECTION(c.program)
        {
            REQUIRE(c.library_counters.size() >= 4);
            const daemon_status_t s = first_status(c, c.lcm_port != 0 ? c.lcm_port : port);
            const std::set<std::string> published(s.counter_names.begin(), s.counter_names.end());
            for (const std::string& name : c.library_counters) {
                INFO(c.program << " publishes " << name);
                CHECK(published.count(name) == 1);
            }
            CHECK(published.count("bus_decode_failures") == 1);  // the runtime's own, appended
            // The host clock's state (docs/time.md), appended by the runtime to every daemon's.
            for (const std::string& name : runtime::counter_names(runtime::HostClockState{})) {
                INFO(c.program << " publishes " << name);
                CHECK(published.count(name) == 1);
            }
            const auto value_of = [&s](const std::string& name) {
                for (std::size_t k = 0; k < s.counter_names.size(); ++k)
                    if (s.counter_names[k] == name) return s.counter_values[k];
                return int64_t{-2};
            };
            // What the kernel says of this machine's clock: a flag and, once read, errors >= 0.
            CHECK((value_of("host_clock_synchronised") == 0 || value_of("host_clock_synchronised") == 1));
            CHECK(value_of("host_clock_max_error_us") >= 0);
            CHECK(value_of("host_clock_test_offset_us") == 0);
        }
        ++port;
    }
}
