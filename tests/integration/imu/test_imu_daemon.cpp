// ugv-imu against `ugv-sim imu` on a pseudo-terminal, over real LCM: imu_t at the emulator's
// rate with the emulator's attitude; an unplug (emulator killed, gone 5 s) and a replug bring
// the daemon back to RUNNING with a reconnect counted; a bad key exits 2 with one line.
// Device faults (issue 11): garbage, a hung unit, bit errors at 1e-3 and 1e-2 per byte,
// frames cut short and a unit on another baud rate never put a wrong sample on the bus.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
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

std::vector<std::string> emulator_args(const std::string& pty, const std::vector<std::string>& extra = {})
{
    // Attitude of the fact-sheet test: roll 10, pitch -5, heading 90 (east); 10 ms ticks.
    std::vector<std::string> args{bin("ugv-sim"), "imu", "--pty", pty, "--roll-deg", "10", "--pitch-deg", "-5",
                                  "--heading-deg", "90", "--timing", "4,10,250,10", "--rate", "50", "--noise-deg",
                                  "0.05", "--streaming"};
    args.insert(args.end(), extra.begin(), extra.end());
    return args;
}

// Whether a published sample is what the emulator of emulator_args() sends: at rest, roll 10,
// pitch 5 nose down, facing east, gravity only (noise 0.05 deg, 0.02 m/s^2, 0.002 rad/s; the
// margins are 10 sigma and more). A frame corrupted in any but its lowest bits fails this.
bool is_emulators(const ugv::imu_t& m)
{
    const double g = std::sqrt(m.acceleration[0] * m.acceleration[0] + m.acceleration[1] * m.acceleration[1] +
                               m.acceleration[2] * m.acceleration[2]);
    return std::fabs(m.roll - 10 * deg) < 0.5 * deg && std::fabs(m.pitch - 5 * deg) < 0.5 * deg &&
           std::fabs(m.yaw) < 0.5 * deg && std::fabs(g - 9.80665) < 0.3 &&
           std::fabs(m.acceleration[2] - 9.80665 * std::cos(10 * deg) * std::cos(5 * deg)) < 0.3 &&
           std::fabs(m.angular_rate[0]) < 0.05 && std::fabs(m.angular_rate[1]) < 0.05 &&
           std::fabs(m.angular_rate[2]) < 0.05;
}

// What the device timer of the samples received says: frames the unit streamed over their span
// but that were not published (it streams one frame every 2 ticks), and steps that are no
// whole number of frames forward (a wrong timer word).
struct TickSteps
{
    int64_t missing = 0;
    std::size_t irregular = 0;
};
TickSteps tick_steps(const std::vector<ugv::imu_t>& imu)
{
    TickSteps t;
    for (std::size_t i = 1; i < imu.size(); ++i) {
        const int64_t step = imu[i].device_ticks - imu[i - 1].device_ticks;
        if (step <= 0 || step % 2 != 0) ++t.irregular;
        else t.missing += step / 2 - 1;
    }
    return t;
}

double seconds_since(std::chrono::steady_clock::time_point t)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// After a unit came back at `back`: waits for the first sample beyond `before` and for a
// RUNNING status, and prints how long each took (not asserted: the machine may be loaded).
void report_return(Listener& listen, std::size_t before, std::chrono::steady_clock::time_point back,
                   const std::string& what)
{
    REQUIRE(listen.until([&] { return listen.got().imu.size() > before; }, 20.0));
    const double first_sample_s = seconds_since(back);
    listen.got().statuses = 0;
    REQUIRE(listen.until([&] { return listen.got().statuses > 0 &&
                                      listen.got().status.state == ugv::daemon_status_t::STATE_RUNNING; },
                         20.0));
    std::printf("imu %s: first sample %.2f s after the unit came back, RUNNING reported after %.2f s\n", what.c_str(),
                first_sample_s, seconds_since(back));
}

std::size_t count_not_emulators(const std::vector<ugv::imu_t>& imu)
{
    return static_cast<std::size_t>(std::count_if(imu.begin(), imu.end(), [](const ugv::imu_t& m) { return !is_emulators(m); }));
}

// ugv-imu against one emulator with the given fault flags, on its own port and folder; the
// unit can be swapped for another (killed, a new one on the same path).
struct ImuRun
{
    TempDir dir;
    std::string pty = dir / "imu";
    std::string url;
    std::unique_ptr<Process> sim;
    std::unique_ptr<Listener> listen;
    std::unique_ptr<Process> daemon;
    int units = 0;

    ImuRun(int port, const std::vector<std::string>& faults, const std::string& extra_config = "") : url(lcm_url(port))
    {
        write_file(dir / "imu.toml", "device = \"" + pty + "\"\nsilence_timeout_ms = 500\n" + extra_config);
        plug_in(faults);
        listen = std::make_unique<Listener>(url);
        daemon = std::make_unique<Process>(std::vector<std::string>{bin("ugv-imu"), "--config", dir / "imu.toml",
                                                                    "--lcm-url", url},
                                           dir / "d.out", dir / "d.err");
    }
    void plug_in(const std::vector<std::string>& faults)
    {
        if (sim) {
            sim->signal(SIGKILL);
            sim->wait_exit(5.0);
            std::filesystem::remove(pty);  // as udev does: a dangling link may point at a reused /dev/pts
        }
        const std::string name = "sim" + std::to_string(++units);
        sim = std::make_unique<Process>(emulator_args(pty, faults), dir / (name + ".out"), dir / (name + ".err"));
        REQUIRE(wait_until([&] { return std::filesystem::exists(pty); }, 10.0));
    }
    // The next status.
    const ugv::daemon_status_t& next_status()
    {
        listen->got().statuses = 0;
        REQUIRE(listen->until([&] { return listen->got().statuses > 0; }, 5.0));
        return listen->got().status;
    }
    void stop()
    {
        daemon->signal(SIGTERM);
        CHECK(daemon->wait_exit(5.0) == 0);
    }
};

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

    // Unplug: the emulator dies with its pty, and stays away for 5 s.
    sim->signal(SIGKILL);
    const auto unplugged = std::chrono::steady_clock::now();
    sim->wait_exit(5.0);
    sim.reset();
    std::filesystem::remove(pty);  // as udev does: a dangling link may point at a reused /dev/pts
    REQUIRE(listen.until([&] { return listen.got().status.state == ugv::daemon_status_t::STATE_DEGRADED; }, 10.0));
    CHECK(daemon.running());
    listen.until([] { return false; }, std::max(0.0, 5.0 - seconds_since(unplugged)));
    const std::size_t before = listen.got().imu.size();

    // Replug: a new emulator on the same path.
    sim = std::make_unique<Process>(emulator_args(pty), dir / "sim2.out", dir / "sim2.err");
    REQUIRE(wait_until([&] { return std::filesystem::exists(pty); }, 10.0));
    report_return(listen, before, std::chrono::steady_clock::now(),
                  "unplugged for " + std::to_string(static_cast<int>(seconds_since(unplugged))) + " s");
    REQUIRE(listen.until([&] { return listen.got().imu.size() > before + 20; }, 20.0));
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
    CHECK(listen.counter("reconnects") == 0);  // silence never reopens the port
    REQUIRE(listen.got().imu.size() > 50);
    // Every published attitude is the emulator's: garbage never became a sample.
    for (const auto& m : listen.got().imu) {
        CHECK(m.yaw == Approx(0.0).margin(0.5 * deg));
        CHECK(m.roll == Approx(10 * deg).margin(0.5 * deg));
    }
    daemon.signal(SIGTERM);
    CHECK(daemon.wait_exit(5.0) == 0);
}

namespace {

// Runs the daemon against a unit whose line flips one bit in a byte with probability rate:
// frames fail their checksum and are dropped. The GX1's checksum is a 16-bit sum of the
// words, so two flips of the same bit weight in opposite directions cancel: such a frame is
// published as it arrived. A Monte Carlo of 0x31 frames gives 6e-6 per frame at 1e-3 and
// 6e-4 at 1e-2 (most of them small); 150 s at 1e-2 through ugv-imu published 1 wrong sample
// of 5977 (roll 55 deg, accel z 30 m/s^2). The session's plausibility check
// (sample_plausibility.hpp) now drops such a sample (`implausible`); a small error within its
// bounds (an accel word off by a few m/s^2) still passes. `undetectable` is how many of those
// a run of this length may show: 0 at 1e-3; at most 1 at 1e-2 (about 0.05 are expected in
// 400 frames).
void run_with_bit_errors(const std::string& rate, int port, std::size_t undetectable)
{
    ImuRun run(port, {"--bit-error-rate", rate, "--seed", "11"});
    Listener& listen = *run.listen;
    INFO(run.daemon->err());
    // 300 samples (6 s at 50 Hz) and at least one frame refused by its checksum.
    REQUIRE(listen.until([&] { return listen.got().imu.size() >= 300 && listen.counter("checksum_errors") > 0; },
                         60.0));
    CHECK(run.next_status().state == ugv::daemon_status_t::STATE_RUNNING);
    CHECK(listen.counter("checksum_errors") > 0);
    CHECK(listen.counter("resyncs") > 0);
    const auto& imu = listen.got().imu;
    const TickSteps ticks = tick_steps(imu);
    const std::size_t wrong = count_not_emulators(imu) + ticks.irregular;
    CHECK(wrong <= undetectable);
    const int64_t missing = ticks.missing;
    std::printf("imu bit error rate %s: %zu samples published (%zu wrong), %lld frames dropped (%.1f %%), "
                "checksum_errors %lld, implausible %lld, resyncs %lld, bytes_skipped %lld\n",
                rate.c_str(), imu.size(), wrong, static_cast<long long>(missing),
                100.0 * static_cast<double>(missing) / static_cast<double>(missing + static_cast<int64_t>(imu.size())),
                static_cast<long long>(listen.counter("checksum_errors")),
                static_cast<long long>(listen.counter("implausible")), static_cast<long long>(listen.counter("resyncs")), static_cast<long long>(listen.counter("bytes_skipped")));
    run.stop();
}

}  // namespace

TEST_CASE("ugv-imu with bit errors at 1e-3 per byte: dropped by the checksum, never published", "[imu][integration]")
{
    run_with_bit_errors("0.001", 7813, 0);
}

TEST_CASE("ugv-imu with bit errors at 1e-2 per byte: dropped by the checksum but for what a 16-bit sum cannot see",
          "[imu][integration]")
{
    run_with_bit_errors("0.01", 7814, 1);
}

TEST_CASE("ugv-imu with every 10th frame cut short: those frames dropped, the stream goes on", "[imu][integration]")
{
    ImuRun run(7815, {"--truncate-every", "10"});
    Listener& listen = *run.listen;
    INFO(run.daemon->err());
    REQUIRE(listen.until([&] { return listen.got().imu.size() >= 270; }, 60.0));
    CHECK(run.next_status().state == ugv::daemon_status_t::STATE_RUNNING);
    const auto& imu = listen.got().imu;
    // Exactly one frame in ten is missing: the cut one, never the whole one after it.
    const TickSteps ticks = tick_steps(imu);
    CHECK(ticks.irregular == 0);
    const int64_t missing = ticks.missing;
    const double streamed = static_cast<double>(missing) + static_cast<double>(imu.size());
    CHECK(static_cast<double>(missing) >= std::floor(streamed / 10.0) - 1);
    CHECK(static_cast<double>(missing) <= std::ceil(streamed / 10.0) + 1);
    // The counters come with the daemon's status, which can be a beat behind the samples
    // (33 checksum errors for 34 frames missing once, on a loaded machine): wait for a
    // status that has counted every frame found missing above.
    listen.until([&] { return listen.counter("checksum_errors") >= missing && listen.counter("resyncs") >= missing; },
                 5.0);
    CHECK(listen.counter("checksum_errors") >= missing);
    CHECK(listen.counter("resyncs") >= missing);
    CHECK(count_not_emulators(imu) == 0);
    std::printf("imu truncated frames: %.0f published, %lld missing of %.0f streamed, checksum_errors %lld\n",
                streamed - static_cast<double>(missing), static_cast<long long>(missing), streamed,
                static_cast<long long>(listen.counter("checksum_errors")));
    run.stop();
}

TEST_CASE("ugv-imu and a unit on another baud rate: DEGRADED naming the rate, nothing published, back when it matches",
          "[imu][integration]")
{
    ImuRun run(7816, {}, "baud = 38400\n");
    Listener& listen = *run.listen;
    INFO(run.daemon->err());
    REQUIRE(listen.until([&] { return listen.got().imu.size() >= 20; }, 20.0));

    // The unit is swapped for one set to 19200 baud: what the daemon reads at 38400 is noise.
    run.plug_in({"--baud", "19200"});
    REQUIRE(listen.until([&] { return listen.got().status.state == ugv::daemon_status_t::STATE_DEGRADED &&
                                      listen.got().status.last_error.find("at 38400 baud") != std::string::npos; },
                         20.0));
    CHECK(listen.got().status.last_error.find("another baud rate") != std::string::npos);
    CHECK(listen.counter("handshake_failures") >= 1);
    // Nothing comes out of the noise: no sample over the next 3 s.
    const std::size_t before = listen.got().imu.size();
    listen.until([] { return false; }, 3.0);
    CHECK(listen.got().imu.size() == before);
    CHECK(run.daemon->running());
    CHECK(run.daemon->err().find("at 38400 baud on " + run.pty) != std::string::npos);

    // The unit set back to 38400.
    run.plug_in({});
    report_return(listen, before, std::chrono::steady_clock::now(), "baud mismatch fixed");
    CHECK(count_not_emulators(listen.got().imu) == 0);
    run.stop();
}

TEST_CASE("ugv-imu when the unit's first 4 handshake replies come cut short: retried, then streaming", "[imu][integration]")
{
    ImuRun run(7817, {"--truncate-replies", "4"});
    Listener& listen = *run.listen;
    INFO(run.daemon->err());
    REQUIRE(listen.until([&] { return listen.got().imu.size() >= 100; }, 60.0));
    CHECK(run.next_status().state == ugv::daemon_status_t::STATE_RUNNING);
    CHECK(listen.counter("checksum_errors") + listen.counter("handshake_failures") > 0);
    CHECK(count_not_emulators(listen.got().imu) == 0);
    CHECK(tick_steps(listen.got().imu).irregular == 0);
    run.stop();
}
