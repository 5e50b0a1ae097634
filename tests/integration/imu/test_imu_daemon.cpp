// ugv-imu against `ugv-sim imu` on a pseudo-terminal, over real LCM: imu_t at the emulator's
// rate with the emulator's attitude; an unplug (emulator killed) and a replug bring the
// daemon back to RUNNING with a reconnect counted; a bad key exits 2 with one line.
#include <catch2/catch.hpp>

#include <cmath>
#include <map>
#include <mutex>
#include <vector>

#include <ugv/daemon_status_t.hpp>
#include <ugv/imu_t.hpp>
#include <ugv/raw_bytes_t.hpp>

#include "ugv/bus/typed.hpp"
#include "ugv/io/clock.hpp"
#include "ugv_test/process.hpp"

using namespace ugv::test;

namespace {

constexpr double pi = 3.14159265358979323846;
constexpr double deg = pi / 180.0;

struct Received
{
    std::vector<ugv::imu_t> imu;
    ugv::daemon_status_t status{};
    int statuses = 0;
    std::vector<uint8_t> raw_to_device;
    std::size_t raw_from_device_bytes = 0;
};

class Listener
{
public:
    explicit Listener(const std::string& url) : bus_(ugv::bus::open_live(url))
    {
        ugv::bus::subscribe<ugv::imu_t>(*bus_, "IMU", [this](const std::string&, const ugv::imu_t& m, int64_t) {
            got_.imu.push_back(m);
        });
        ugv::bus::subscribe<ugv::daemon_status_t>(*bus_, "STATUS_IMU",
                                                  [this](const std::string&, const ugv::daemon_status_t& m, int64_t) {
                                                      got_.status = m;
                                                      ++got_.statuses;
                                                  });
        ugv::bus::subscribe<ugv::raw_bytes_t>(*bus_, "RAW_IMU", [this](const std::string&, const ugv::raw_bytes_t& m,
                                                                       int64_t) {
            if (m.direction == ugv::raw_bytes_t::DIRECTION_TO_DEVICE)
                got_.raw_to_device.insert(got_.raw_to_device.end(), m.data.begin(), m.data.end());
            else
                got_.raw_from_device_bytes += m.data.size();
        });
    }
    // Handles traffic until pred() holds or timeout_s passes.
    template <typename Pred>
    bool until(Pred pred, double timeout_s)
    {
        const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
        while (!pred() && std::chrono::steady_clock::now() < end) bus_->handle(20);
        return pred();
    }
    Received& got() { return got_; }
    int64_t counter(const std::string& name) const
    {
        for (int i = 0; i < got_.status.ncounters; ++i)
            if (got_.status.counter_names[static_cast<std::size_t>(i)] == name)
                return got_.status.counter_values[static_cast<std::size_t>(i)];
        return -1;
    }

private:
    std::unique_ptr<ugv::bus::Bus> bus_;
    Received got_;
};

std::vector<std::string> emulator_args(const std::string& pty)
{
    // Attitude of the fact-sheet test: roll 10, pitch -5, heading 90 (east); 10 ms ticks.
    return {bin("ugv-sim"), "imu", "--pty", pty, "--roll-deg", "10", "--pitch-deg", "-5", "--heading-deg", "90",
            "--timing", "4,10,250,10", "--rate", "50", "--noise-deg", "0.05", "--streaming"};
}

}  // namespace

TEST_CASE("ugv-imu publishes the emulator's attitude at its rate and survives an unplug", "[imu][integration]")
{
    TempDir dir;
    const std::string pty = dir / "imu";
    const std::string url = lcm_url(7810);
    write_file(dir / "imu.toml", "device = \"" + pty + "\"\nsilence_timeout_ms = 500\norientation_sigma_deg = 2.0\n"
                              "publish_raw = true\n");
    auto sim = std::make_unique<Process>(emulator_args(pty), dir / "sim1.out", dir / "sim1.err");
    REQUIRE(wait_until([&] { return std::filesystem::exists(pty); }, 10.0));
    Listener listen(url);
    Process daemon({bin("ugv-imu"), "--config", dir / "imu.toml", "--lcm-url", url}, dir / "d.out", dir / "d.err");

    // Data flows: collect two seconds' worth at 50 Hz.
    INFO(daemon.err());
    REQUIRE(listen.until([&] { return listen.got().imu.size() >= 100; }, 20.0));
    const auto& imu = listen.got().imu;
    const ugv::imu_t& first = imu.front();
    const ugv::imu_t& last = imu.back();
    // Rate from the measurement stamps (device timer through the clock filter): 50 Hz.
    const double span_s = static_cast<double>(last.utime - first.utime) * 1e-6;
    const double rate_hz = static_cast<double>(last.seq - first.seq) / span_s;
    CHECK(rate_hz == Approx(50.0).epsilon(0.02));
    CHECK(last.seq - first.seq == static_cast<int64_t>(imu.size()) - 1);  // none lost on the way
    CHECK(last.device_ticks - first.device_ticks == 2 * (last.seq - first.seq));
    // The attitude in project convention: roll 10, pitch +5 (nose down), ENU yaw 0 (east).
    CHECK(last.roll == Approx(10 * deg).margin(0.5 * deg));
    CHECK(last.pitch == Approx(5 * deg).margin(0.5 * deg));
    CHECK(last.yaw == Approx(0.0).margin(0.5 * deg));
    CHECK(last.orientation[0] == Approx(0.99525).margin(0.005));
    CHECK(last.orientation[1] == Approx(0.08707).margin(0.005));
    CHECK(last.orientation[2] == Approx(0.04345).margin(0.005));
    CHECK(last.orientation[3] == Approx(-0.00380).margin(0.005));
    CHECK(last.acceleration[2] == Approx(9.80665 * std::cos(10 * deg) * std::cos(5 * deg)).margin(0.2));
    CHECK(std::isnan(last.magnetic_field[0]));  // 0x31 carries no magnetometer
    CHECK(last.valid == (int32_t{ugv::imu_t::VALID_ORIENTATION} | int32_t{ugv::imu_t::VALID_EULER} |
                         int32_t{ugv::imu_t::VALID_ANGULAR_RATE} | int32_t{ugv::imu_t::VALID_ACCELERATION}));
    CHECK(last.orientation_sigma == Approx(2 * deg));
    CHECK(std::abs(last.utime - ugv::io::now_utime()) < 1'000'000);

    REQUIRE(listen.until([&] { return listen.got().status.state == ugv::daemon_status_t::STATE_RUNNING &&
                                      listen.counter("frames") > 0; },
                         5.0));
    CHECK(listen.counter("checksum_errors") == 0);
    // The raw capture: the handshake as sent (stop first), and the stream as received.
    REQUIRE(listen.got().raw_to_device.size() >= 3);
    CHECK(listen.got().raw_to_device[0] == 0x10);
    CHECK(listen.got().raw_to_device[2] == 0x00);
    CHECK(listen.got().raw_from_device_bytes >= 100 * 23);
    CHECK(listen.counter("reconnects") == 0);

    // Unplug: the emulator dies with its pty.
    sim->signal(SIGKILL);
    sim->wait_exit(5.0);
    sim.reset();
    REQUIRE(listen.until([&] { return listen.got().status.state == ugv::daemon_status_t::STATE_DEGRADED; }, 10.0));
    CHECK(daemon.running());

    // Replug: a new emulator on the same path.
    sim = std::make_unique<Process>(emulator_args(pty), dir / "sim2.out", dir / "sim2.err");
    const std::size_t before = listen.got().imu.size();
    REQUIRE(listen.until([&] { return listen.got().status.state == ugv::daemon_status_t::STATE_RUNNING &&
                                      listen.got().imu.size() > before + 20; },
                         20.0));
    CHECK(listen.counter("reconnects") >= 1);
    CHECK(listen.got().imu.back().seq > last.seq);  // the sequence goes on

    daemon.signal(SIGTERM);
    CHECK(daemon.wait_exit(5.0) == 0);
}

TEST_CASE("ugv-imu rejects a bad key with exit status 2 and one line", "[imu][integration]")
{
    TempDir dir;
    write_file(dir / "bad.toml", "command = 0x55\n");
    Process daemon({bin("ugv-imu"), "--config", dir / "bad.toml", "--lcm-url", lcm_url(7811)}, dir / "o", dir / "e");
    CHECK(daemon.wait_exit(10.0) == 2);
    CHECK(daemon.err().find("command") != std::string::npos);
    write_file(dir / "typo.toml", "chanel = \"IMU\"\n");
    Process typo({bin("ugv-imu"), "--config", dir / "typo.toml", "--lcm-url", lcm_url(7811)}, dir / "o2", dir / "e2");
    CHECK(typo.wait_exit(10.0) == 2);
    CHECK(typo.err().find("chanel") != std::string::npos);
}

TEST_CASE("ugv-imu through garbage and a hung unit: nothing bad published, back to RUNNING", "[imu][integration]")
{
    TempDir dir;
    const std::string pty = dir / "imu";
    const std::string url = lcm_url(7812);
    write_file(dir / "imu.toml", "device = \"" + pty + "\"\nsilence_timeout_ms = 500\n");
    auto args = emulator_args(pty);
    for (const char* a : {"--garbage-every", "0.1", "--garbage-bytes", "30", "--silence-after", "3", "--silence-for", "2"})
        args.emplace_back(a);
    Process sim(args, dir / "sim.out", dir / "sim.err");
    REQUIRE(wait_until([&] { return std::filesystem::exists(pty); }, 10.0));
    Listener listen(url);
    Process daemon({bin("ugv-imu"), "--config", dir / "imu.toml", "--lcm-url", url}, dir / "d.out", dir / "d.err");
    INFO(daemon.err());

    REQUIRE(listen.until([&] { return listen.got().status.state == ugv::daemon_status_t::STATE_DEGRADED; }, 20.0));
    CHECK(listen.counter("resyncs") > 0);
    CHECK(listen.counter("bytes_skipped") > 0);
    REQUIRE(listen.until([&] { return listen.got().status.state == ugv::daemon_status_t::STATE_RUNNING; }, 20.0));
    CHECK(listen.counter("silences") >= 1);
    REQUIRE(listen.got().imu.size() > 50);
    // Every published attitude is the emulator's: garbage never became a sample.
    for (const auto& m : listen.got().imu) {
        CHECK(m.yaw == Approx(0.0).margin(0.5 * deg));
        CHECK(m.roll == Approx(10 * deg).margin(0.5 * deg));
    }
    daemon.signal(SIGTERM);
    CHECK(daemon.wait_exit(5.0) == 0);
}
