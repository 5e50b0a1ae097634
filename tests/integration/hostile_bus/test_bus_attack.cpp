// Issue 23, the bus: fragment headers that claim huge messages, sent to the group from 64
// source ports while the real ugv-servo (with its drive emulator) and the real ugv-terrain
// (fed a synthetic drive) run on it. First the 64 headers of the report (20 bytes each,
// each claiming a 65 MB message), then 10,000 more, half claiming 65 MB and half claiming
// 1 MB with 1000 bytes of payload (held, then evicted or expired), with valid traffic in
// between. The daemon's own output must not pause, its memory must stay flat, the valid
// messages must get through, and the attack must show in its STATUS counters.
#include <catch2/catch.hpp>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <pthread.h>
#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <numbers>
#include <string>
#include <thread>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "../terrain/synthetic_log.hpp"
#include "ugv/bus/typed.hpp"
#include "ugv/daemon_status_t.hpp"
#include "ugv/io/clock.hpp"
#include "ugv/servo_command_t.hpp"
#include "ugv/servo_state_t.hpp"
#include "ugv_test/process.hpp"

using namespace ugv;

namespace {

constexpr int kSenders = 64;
constexpr int kHeaders = 10'000;
constexpr uint32_t kHugeClaim = 65'000'000;  // the report's 65 MB (LCM's own cap is 64 MiB)
constexpr uint32_t kBigClaim = 1'000'000;    // within bus_max_message_bytes (1 MiB)

std::vector<uint8_t> lc03(uint32_t seq, uint32_t size, uint32_t offset, uint16_t no, uint16_t count, std::size_t bytes)
{
    std::vector<uint8_t> b{'L', 'C', '0', '3'};
    for (uint32_t v : {seq, size, offset})
        for (int s = 24; s >= 0; s -= 8) b.push_back(static_cast<uint8_t>(v >> s));
    for (uint16_t v : {no, count}) {
        b.push_back(static_cast<uint8_t>(v >> 8));
        b.push_back(static_cast<uint8_t>(v));
    }
    b.resize(b.size() + bytes, 0x5a);
    return b;
}

// The attack, on a thread of its own: 64 sockets, so 64 source ports (64 senders).
class Attack
{
public:
    explicit Attack(uint16_t port)
    {
        to_.sin_family = AF_INET;
        to_.sin_port = htons(port);
        inet_pton(AF_INET, "239.255.76.67", &to_.sin_addr);
        const unsigned char ttl = 0, loop = 1;
        for (int k = 0; k < kSenders; ++k) {
            const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
            ::setsockopt(fd, IPPROTO_IP, IP_MULTICAST_TTL, &ttl, sizeof ttl);
            ::setsockopt(fd, IPPROTO_IP, IP_MULTICAST_LOOP, &loop, sizeof loop);
            fds_.push_back(fd);
        }
    }
    ~Attack()
    {
        if (thread_.joinable()) thread_.join();
        for (int fd : fds_) ::close(fd);
    }
    void start()
    {
        thread_ = std::thread([this] {
            const sched_param normal{};
            pthread_setschedparam(pthread_self(), SCHED_OTHER, &normal);  // whatever the test thread has
            run();
        });
    }
    bool done() const { return done_.load(); }
    int sent() const { return sent_.load(); }
    // Of the 10,000: how many claim 65 MB and how many 1 MB.
    static constexpr int kHuge = 64 + kHeaders / 2;
    static constexpr int kBig = kHeaders / 2;

private:
    void send(int sender, const std::vector<uint8_t>& d)
    {
        if (::sendto(fds_[static_cast<std::size_t>(sender)], d.data(), d.size(), 0, reinterpret_cast<const sockaddr*>(&to_),
                     sizeof to_) == static_cast<ssize_t>(d.size()))
            ++sent_;
    }
    void run()
    {
        // The report's 64: fragment 1 of 1000 (no channel, no payload: 20 bytes), 65 MB claimed.
        for (int k = 0; k < kSenders; ++k) send(k, lc03(1, kHugeClaim, 65'000, 1, 1000, 0));
        std::this_thread::sleep_for(std::chrono::milliseconds(300));
        // 10,000 more in bursts of 50 every 10 ms (5,000 a second, for 2 s): as fast as
        // a daemon's 2 MiB socket buffer takes them while it is busy for a moment.
        for (int k = 0; k < kHeaders; ++k) {
            const int sender = (k / 2) % kSenders;  // both kinds from all 64
            const uint32_t seq = 2 + static_cast<uint32_t>(k);
            if (k % 2 == 0) send(sender, lc03(seq, kHugeClaim, 65'000, 1, 1000, 0));
            else send(sender, lc03(seq, kBigClaim, 65'000, 1, 16, 1000));
            if (k % 50 == 49) std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        done_.store(true);
    }

    sockaddr_in to_{};
    std::vector<int> fds_;
    std::thread thread_;
    std::atomic<bool> done_{false};
    std::atomic<int> sent_{0};
};

double ms(int64_t us) { return static_cast<double>(us) / 1000.0; }

int64_t rss_kb(pid_t pid)
{
    std::ifstream in("/proc/" + std::to_string(pid) + "/status");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind("VmRSS:", 0) == 0) return std::stoll(line.substr(6));
    return -1;
}

// What the test hears: arrival times (the kernel's receive stamps, so the test's own
// scheduling does not matter) of the daemon's output, and its latest STATUS.
struct Observer
{
    std::unique_ptr<bus::Bus> bus;
    std::map<std::string, std::vector<int64_t>> arrivals;
    daemon_status_t status{};
    int64_t status_recv = 0;

    Observer(const std::string& url, const std::vector<std::string>& outputs, const std::string& status_channel)
        : bus(bus::open_live(url))
    {
        for (const auto& channel : outputs)
            bus->subscribe(channel, [this](const std::string& ch, const uint8_t*, std::size_t, int64_t recv_utime) {
                arrivals[ch].push_back(recv_utime);
            });
        bus::subscribe<daemon_status_t>(*bus, status_channel,
                                        [this](const std::string&, const daemon_status_t& m, int64_t recv_utime) {
                                            status = m;
                                            status_recv = recv_utime;
                                        });
    }
    void pump(double seconds)
    {
        const int64_t until = io::monotonic_us() + static_cast<int64_t>(seconds * 1e6);
        while (io::monotonic_us() < until) bus->handle(5);
    }
    bool until(const std::function<bool()>& pred, double timeout_s)
    {
        const int64_t until = io::monotonic_us() + static_cast<int64_t>(timeout_s * 1e6);
        while (io::monotonic_us() < until) {
            bus->handle(5);
            if (pred()) return true;
        }
        return false;
    }
    // A status published after now.
    bool fresh_status(double timeout_s)
    {
        const int64_t now = io::now_utime();
        return until([&] { return status_recv > now; }, timeout_s);
    }
    int64_t counter(const std::string& name) const
    {
        for (int i = 0; i < status.ncounters; ++i)
            if (status.counter_names[static_cast<std::size_t>(i)] == name)
                return status.counter_values[static_cast<std::size_t>(i)];
        return -1;
    }
    // The longest gap between arrivals on channel within [from, to] (the edges count).
    int64_t max_gap_us(const std::string& channel, int64_t from, int64_t to) const
    {
        int64_t last = from, gap = 0;
        for (int64_t t : arrivals.at(channel)) {
            if (t < from) continue;
            if (t > to) break;
            gap = std::max(gap, t - last);
            last = t;
        }
        return std::max(gap, to - last);
    }
};

// The test's own thread at real-time priority (below the daemons') while it lives: a starved
// observer would lose outputs among the attack's datagrams and see gaps the daemon did not
// make. The attack's thread stays at normal priority.
struct RealTimeObserver
{
    bool on = false;
    RealTimeObserver()
    {
        const sched_param rt{40};
        on = pthread_setschedparam(pthread_self(), SCHED_FIFO, &rt) == 0;
    }
    ~RealTimeObserver()
    {
        const sched_param normal{};
        pthread_setschedparam(pthread_self(), SCHED_OTHER, &normal);
    }
    RealTimeObserver(const RealTimeObserver&) = delete;
    RealTimeObserver& operator=(const RealTimeObserver&) = delete;
};

// The attack's counters, checked on a daemon's STATUS once the attack is over and every
// message it began has expired.
void check_attack_counted(const Observer& o, int sent)
{
    INFO("attack datagrams sent " << sent);
    REQUIRE(sent == Attack::kHuge + Attack::kBig);
    // Every datagram read, none dropped by the kernel on a machine that is not starved;
    // a few lost to a stall must not fail the test (the gaps say whether it stalled).
    const int64_t oversized = o.counter("bus_oversized_messages");
    const int64_t let_go =
        o.counter("bus_evicted_messages") + o.counter("bus_expired_messages") + o.counter("bus_incomplete_messages");
    INFO("oversized " << oversized << ", evicted " << o.counter("bus_evicted_messages") << ", expired "
                      << o.counter("bus_expired_messages") << ", incomplete " << o.counter("bus_incomplete_messages"));
    CHECK(oversized <= Attack::kHuge);
    CHECK(oversized >= Attack::kHuge * 98 / 100);
    CHECK(let_go <= Attack::kBig);
    CHECK(let_go >= Attack::kBig * 98 / 100);
    CHECK(o.counter("bus_evicted_messages") > 0);  // 64 senders, 32 slots
    CHECK(o.counter("bus_reassembly_bytes") == 0);  // all expired
    CHECK(o.counter("bus_invalid_datagrams") == 0);
}

}  // namespace

TEST_CASE("ugv-servo under the fragment-header attack: SERVO_STATE does not pause, memory stays flat")
{
    test::TempDir dir;
    const uint16_t port = 7711;
    const std::string url = test::lcm_url(port);
    const std::string pty = dir / "servo.pty";
    // Real-time scheduling, as deployed (the servo's default config has fifo_priority 50), and
    // for the emulated drive, which stands for hardware with a CPU of its own: the gaps then
    // show what the daemon does under the attack, not what a loaded test machine does to it.
    test::Process sim({"/usr/bin/chrt", "-f", "50", test::bin("ugv-sim"), "servo", "--pty", pty, "--node-id", "3"},
                      dir / "sim.out", dir / "sim.err");
    REQUIRE(test::wait_until([&] { return std::filesystem::exists(pty); }, 10.0));
    test::write_file(dir / "servo.toml",
                     "transport = \"slcan:" + pty + "@115200\"\n"
                     "bitrate = 500000\nnode_id = 3\nmin_tilt_deg = -10.0\nmax_tilt_deg = 40.0\n"
                     "heartbeat_ms = 300\nsdo_timeout_ms = 500\n"
                     "[profile]\nkind = \"CONSTANT_RATE\"\nnod_min_deg = 0.0\nnod_max_deg = 20.0\n"
                     "rate_deg_s = 40.0\n[realtime]\nfifo_priority = 50\n");
    const RealTimeObserver observer_rt;
    Observer o(url + "&recv_buf_size=4194304", {"SERVO_STATE"}, "STATUS_SERVO");
    test::Process servo({test::bin("ugv-servo"), "--config", dir / "servo.toml", "--lcm-url", url},
                        dir / "servo.out", dir / "servo.err");
    servo_state_t last{};
    std::vector<std::pair<int64_t, int64_t>> seqs;  // receive time, seq
    bus::subscribe<servo_state_t>(*o.bus, "SERVO_STATE", [&](const std::string&, const servo_state_t& m, int64_t t) {
        last = m;
        seqs.emplace_back(t, m.seq);
    });
    REQUIRE(o.until([&] { return last.cia402_state == servo_state_t::STATE_OPERATION_ENABLED; }, 20.0));

    // Settled; then a quiet second as the baseline.
    o.pump(1.0);
    const int64_t rss_before = rss_kb(servo.pid());
    const int64_t quiet_from = io::now_utime();
    o.pump(1.0);
    const int64_t quiet_gap = o.max_gap_us("SERVO_STATE", quiet_from, io::now_utime());

    // The attack, with a valid SERVO_COMMAND every 100 ms meanwhile.
    Attack attack(port);
    const int64_t attack_from = io::now_utime();
    attack.start();
    servo_command_t cmd{};
    cmd.profile = servo_command_t::PROFILE_CONSTANT_RATE;
    cmd.min_tilt = 0.0;
    cmd.max_tilt = 20 * std::numbers::pi / 180;
    cmd.rate = 40 * std::numbers::pi / 180;
    int commands = 0;
    while (!attack.done()) {
        cmd.utime = io::now_utime();
        cmd.seq = commands++;
        bus::publish(*o.bus, "SERVO_COMMAND", cmd);
        o.pump(0.1);
    }
    const int64_t attack_to = io::now_utime();
    // Unfinished messages expire after 1 s; then a status that says so.
    o.pump(1.5);
    REQUIRE(o.fresh_status(3.0));
    const int64_t rss_after = rss_kb(servo.pid());

    const int64_t gap = o.max_gap_us("SERVO_STATE", attack_from, attack_to);
    int lost = 0;  // by the observer: seq jumps
    for (std::size_t i = 1; i < seqs.size(); ++i)
        if (seqs[i].first >= attack_from && seqs[i].first <= attack_to && seqs[i].second != seqs[i - 1].second + 1) ++lost;
    INFO("observer real-time: " << observer_rt.on << "; SERVO_STATE lost by the observer: " << lost);
    INFO("SERVO_STATE max gap: quiet " << ms(quiet_gap) << " ms, under attack " << ms(gap)
                                       << " ms; RSS " << rss_before << " -> " << rss_after << " kB; " << commands
                                       << " commands");
    // The goal: no pause beyond two 10 ms control ticks (the report: 20.7 s); the tick reading
    // the drive's 100 Hz TPDOs gives gaps of up to ~20 ms with no attack at all. Most runs
    // stay there, a few show one pause of ~100 ms under the attack (docs/reliability.md,
    // section 5): the bound is 25 ticks, far below the report's seconds.
    CHECK(gap <= 250'000);
    CHECK(rss_after - rss_before <= 4096);
    CHECK(servo.running());
    CHECK(o.status.state == daemon_status_t::STATE_RUNNING);
    // Every command got through: the servo subscribes to nothing else.
    CHECK(o.counter("commands_accepted") == commands);
    CHECK(o.counter("bus_received") == commands);
    check_attack_counted(o, attack.sent());

    servo.signal(SIGTERM);
    CHECK(servo.wait_exit(5.0) == 0);
}

TEST_CASE("ugv-terrain under the fragment-header attack: maps and STATUS do not pause, memory stays flat")
{
    test::TempDir dir;
    const uint16_t port = 7712;
    const std::string url = test::lcm_url(port);
    test::write_file(dir / "terrain.toml", "publish_hz = 5.0\n");
    const RealTimeObserver observer_rt;
    Observer o(url + "&recv_buf_size=4194304", {"TERRAIN_MAP", "STATUS_TERRAIN"}, "STATUS_TERRAIN");
    test::Process terrain({test::bin("ugv-terrain"), "--config", dir / "terrain.toml", "--lcm-url", url},
                          dir / "terrain.out", dir / "terrain.err");
    REQUIRE(o.fresh_status(15.0));

    // The synthetic drive, live, stamped from now on, from a thread of its own.
    test::SyntheticDrive drive;
    drive.duration_s = 9.0;
    drive.start_utime = io::now_utime() + 100'000;
    std::atomic<int> published{0};
    std::atomic<bool> drive_done{false};
    std::thread driver([&] {
        lcm::LCM out(url);
        drive.events([&](const std::string& channel, int64_t utime, const std::vector<uint8_t>& bytes) {
            const int64_t wait = utime - io::now_utime();
            if (wait > 0) std::this_thread::sleep_for(std::chrono::microseconds(wait));
            if (out.publish(channel, bytes.data(), static_cast<unsigned>(bytes.size())) == 0) ++published;
        });
        drive_done.store(true);
    });

    o.pump(2.5);
    const int64_t rss_before = rss_kb(terrain.pid());
    const int64_t quiet_from = io::now_utime();
    o.pump(1.0);
    const int64_t quiet_to = io::now_utime();

    Attack attack(port);
    const int64_t attack_from = io::now_utime();
    attack.start();
    REQUIRE(o.until([&] { return attack.done(); }, 30.0));
    const int64_t attack_to = io::now_utime();
    REQUIRE(o.until([&] { return drive_done.load(); }, 30.0));
    driver.join();
    o.pump(0.5);  // the last inputs read; unfinished messages expired (1 s after the attack)
    REQUIRE(o.fresh_status(3.0));
    const int64_t rss_after = rss_kb(terrain.pid());

    const int64_t map_gap = o.max_gap_us("TERRAIN_MAP", attack_from, attack_to);
    const int64_t status_gap = o.max_gap_us("STATUS_TERRAIN", attack_from, attack_to);
    INFO("TERRAIN_MAP max gap: quiet " << ms(o.max_gap_us("TERRAIN_MAP", quiet_from, quiet_to))
                                       << " ms, under attack " << ms(map_gap) << " ms; STATUS max gap "
                                       << ms(status_gap) << " ms; RSS " << rss_before << " -> " << rss_after
                                       << " kB");
    // Maps every 200 ms of message time (drained every 50 ms: gaps of 250 ms with no attack),
    // STATUS every second (the report: no STATUS for 28 s). Bounds with room for a loaded
    // machine: three map periods, two status periods.
    CHECK(map_gap <= 600'000);
    CHECK(status_gap <= 2'000'000);
    CHECK(rss_after - rss_before <= 4096);
    CHECK(terrain.running());
    CHECK(o.status.state == daemon_status_t::STATE_RUNNING);
    // Every POSE and POINTS of the drive got through.
    CHECK(o.counter("bus_received") == published.load());
    check_attack_counted(o, attack.sent());

    terrain.signal(SIGTERM);
    CHECK(terrain.wait_exit(10.0) == 0);
}

TEST_CASE("bus_max_message_bytes reaches the daemon's bus, and out of range it is a config error")
{
    test::TempDir dir;
    const uint16_t port = 7713;
    const std::string url = test::lcm_url(port);
    test::write_file(dir / "small.toml", "bus_max_message_bytes = 65536\n");
    Observer o(url, {}, "STATUS_TERRAIN");
    test::Process terrain({test::bin("ugv-terrain"), "--config", dir / "small.toml", "--lcm-url", url},
                          dir / "terrain.out", dir / "terrain.err");
    REQUIRE(o.fresh_status(15.0));
    CHECK(o.counter("bus_oversized_messages") == 0);
    // 100 kB on POSE: liblcm sends 2 fragments, each refused (the message is over 64 KiB).
    const std::vector<uint8_t> big(100'000, 1);
    REQUIRE(o.bus->publish("POSE", big.data(), big.size()));
    REQUIRE(o.fresh_status(3.0));
    REQUIRE(o.fresh_status(3.0));
    CHECK(o.counter("bus_oversized_messages") == 2);
    CHECK(o.counter("bus_decode_failures") == 0);  // never reached the handler
    terrain.signal(SIGTERM);
    CHECK(terrain.wait_exit(10.0) == 0);

    test::write_file(dir / "tiny.toml", "bus_max_message_bytes = 1000\n");
    CHECK(test::run({test::bin("ugv-terrain"), "--config", dir / "tiny.toml", "--lcm-url", url}, dir / "o.txt",
                    dir / "e.txt", 10.0) == 2);
    CHECK(test::read_file(dir / "e.txt") ==
          dir / "tiny.toml" + ": bus_max_message_bytes: 1000 is out of range [65536, 67108864]\n");
}
