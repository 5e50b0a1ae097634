// ugv-terrain live on LCM (udpm, this test's own port): poses and clouds in, maps and
// STATUS_TERRAIN out, a clean exit on SIGTERM.
#include <catch2/catch.hpp>

#include <lcm/lcm-cpp.hpp>

#include <chrono>
#include <csignal>
#include <thread>

#include <ugv/daemon_status_t.hpp>
#include <ugv/terrain_map_t.hpp>

#include "synthetic_log.hpp"
#include "ugv_test/process.hpp"

using namespace ugv;

TEST_CASE("ugv-terrain maps live traffic and reports its counters")
{
    test::TempDir dir;
    const std::string url = test::lcm_url(7950);
    const std::string config = dir / "terrain.toml";
    // The drive below runs at ~4x real time from now: stamps may lead the clock by more than
    // the default bound of 2 s.
    test::write_file(config, "publish_hz = 10.0\nmax_stamp_ahead_s = 60.0\n");
    // A map (~270 kB) is larger than the default receive buffer (208 kB): with it, a map
    // arriving while this thread publishes the drive was lost whole.
    lcm::LCM bus(url + "&recv_buf_size=4194304");
    REQUIRE(bus.good());
    int maps = 0, statuses = 0;
    terrain_map_t last_map;
    int64_t points_fused = 0, maps_published = 0;
    auto on_map = [&](const lcm::ReceiveBuffer* rbuf, const std::string&) {
        if (last_map.decode(rbuf->data, 0, static_cast<int>(rbuf->data_size)) == static_cast<int>(rbuf->data_size)) ++maps;
    };
    auto on_status = [&](const lcm::ReceiveBuffer* rbuf, const std::string&) {
        daemon_status_t s;
        if (s.decode(rbuf->data, 0, static_cast<int>(rbuf->data_size)) != static_cast<int>(rbuf->data_size)) return;
        ++statuses;
        for (int k = 0; k < s.ncounters; ++k)
        {
            const std::string& name = s.counter_names[static_cast<std::size_t>(k)];
            if (name == "points_fused") points_fused = s.counter_values[static_cast<std::size_t>(k)];
            if (name == "maps_published") maps_published = s.counter_values[static_cast<std::size_t>(k)];
        }
    };
    struct Handler
    {
        std::function<void(const lcm::ReceiveBuffer*, const std::string&)> fn;
        void handle(const lcm::ReceiveBuffer* rbuf, const std::string& channel) { fn(rbuf, channel); }
    } map_handler{on_map}, status_handler{on_status};
    bus.subscribe("TERRAIN_MAP", &Handler::handle, &map_handler);
    bus.subscribe("STATUS_TERRAIN", &Handler::handle, &status_handler);

    test::Process daemon({test::bin("ugv-terrain"), "--config", config, "--lcm-url", url}, dir / "out.txt",
                         dir / "err.txt");
    auto pump = [&](double seconds) {
        const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
        while (std::chrono::steady_clock::now() < end) bus.handleTimeout(10);
    };
    // Up when its first status arrives.
    const auto up_by = std::chrono::steady_clock::now() + std::chrono::seconds(15);
    while (statuses == 0 && std::chrono::steady_clock::now() < up_by && daemon.running()) bus.handleTimeout(50);
    INFO(daemon.err());
    REQUIRE(statuses > 0);

    test::SyntheticDrive drive;
    drive.duration_s = 2.0;
    drive.start_utime = std::chrono::duration_cast<std::chrono::microseconds>(
                            std::chrono::system_clock::now().time_since_epoch())
                            .count();
    drive.events([&](const std::string& channel, int64_t, const std::vector<uint8_t>& bytes) {
        bus.publish(channel, bytes.data(), static_cast<unsigned>(bytes.size()));
        pump(0.004);  // ~4x real time, gentle on the UDP buffers
    });
    const auto done_by = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while ((maps_published < 15 || maps == 0) && std::chrono::steady_clock::now() < done_by) bus.handleTimeout(50);
    // 2 s of message time at 10 Hz: about 20 maps published (the daemon's count). A 270 kB map
    // is ~40 UDP fragments, so on a loaded machine some do not reach this process: at least one must.
    CHECK(maps_published >= 15);
    CHECK(maps >= 1);
    CHECK(points_fused > 0);
    CHECK(last_map.nx == 150);
    CHECK(last_map.ncells == 150 * 150);
    CHECK(last_map.pose.utime == last_map.utime);

    daemon.signal(SIGTERM);
    CHECK(daemon.wait_exit(5.0) == 0);
}
