// ugv-foxglove with a client that subscribes to the terrain maps and then never reads (a raw
// socket after the WebSocket handshake): the daemon's memory stays bounded, the frames it
// could not queue are counted, and nothing is encoded while no client subscribes.
#include <catch2/catch.hpp>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <lcm/lcm-cpp.hpp>

#include <cstdio>
#include <fstream>
#include <map>
#include <thread>
#include <vector>

#include "bridge.hpp"
#include "ugv/daemon_status_t.hpp"
#include "ugv/terrain_map_t.hpp"
#include "ugv_test/process.hpp"

using namespace ugv;

namespace {

constexpr int kSlowPort = 18761, kSlowLcm = 7935;

// The daemon's counters from its last STATUS_FOXGLOVE, waited for.
class StatusReader
{
public:
    explicit StatusReader(int lcm_port) : lcm_(test::lcm_url(lcm_port))
    {
        lcm_.subscribe("STATUS_FOXGLOVE", &StatusReader::on_status, this);
    }
    // Reads statuses for up to timeout_s until pred(counters) holds.
    template <typename Pred>
    bool wait(Pred pred, double timeout_s)
    {
        return test::wait_until(
            [&] {
                while (lcm_.handleTimeout(0) > 0) {}
                return !counters.empty() && pred(counters);
            },
            timeout_s);
    }
    std::map<std::string, int64_t> counters;

private:
    void on_status(const lcm::ReceiveBuffer*, const std::string&, const daemon_status_t* s)
    {
        for (int k = 0; k < s->ncounters; ++k) counters[s->counter_names[k]] = s->counter_values[k];
    }
    lcm::LCM lcm_;
};

int64_t rss_kb(pid_t pid)
{
    std::ifstream in("/proc/" + std::to_string(pid) + "/status");
    for (std::string line; std::getline(in, line);)
        if (line.rfind("VmRSS:", 0) == 0) return std::stoll(line.substr(6));
    return -1;
}

// The id of an advertised topic in what the server sent (nlohmann dumps keys in order: "id"
// comes before "topic" in each channel); 0 when absent.
uint32_t advertised_id(const std::string& sent, const std::string& topic)
{
    const std::size_t at = sent.find("\"topic\":\"" + topic + "\"");
    if (at == std::string::npos) return 0;
    const std::size_t id = sent.rfind("\"id\":", at);
    return id == std::string::npos ? 0 : static_cast<uint32_t>(std::stoul(sent.substr(id + 5)));
}

// A WebSocket client by hand: the handshake, the advertised topics read, one subscription to
// each of `topics`, and then it never reads again.
int stalled_client(int port, const std::vector<std::string>& topics)
{
    const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    const int small = 4096;
    ::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &small, sizeof small);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_port = htons(static_cast<uint16_t>(port));
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    REQUIRE(::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0);
    const std::string hello = "GET / HTTP/1.1\r\nHost: 127.0.0.1\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
                              "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n"
                              "Sec-WebSocket-Protocol: foxglove.websocket.v1\r\n\r\n";
    REQUIRE(::write(fd, hello.data(), hello.size()) == static_cast<ssize_t>(hello.size()));
    std::string sent;
    char buf[65536];
    timeval tv{0, 200'000};
    ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &tv, sizeof tv);
    std::string subscribe = "{\"op\":\"subscribe\",\"subscriptions\":[";
    for (std::size_t k = 0; k < topics.size(); ++k) {
        uint32_t id = 0;
        REQUIRE(test::wait_until(
            [&] {
                const ssize_t n = ::read(fd, buf, sizeof buf);
                if (n > 0) sent.append(buf, static_cast<std::size_t>(n));
                return (id = advertised_id(sent, topics[k])) != 0;
            },
            10));
        subscribe += (k ? ",{\"id\":" : "{\"id\":") + std::to_string(k + 1) + ",\"channelId\":" + std::to_string(id) + "}";
    }
    subscribe += "]}";
    REQUIRE(sent.rfind("HTTP/1.1 101", 0) == 0);
    // A masked text frame (mask 0: the payload as it is), the length in its shortest form.
    std::string frame = {'\x81'};
    if (subscribe.size() < 126) {
        frame += static_cast<char>(0x80 | subscribe.size());
    } else {
        frame += {static_cast<char>(0x80 | 126), static_cast<char>(subscribe.size() >> 8),
                  static_cast<char>(subscribe.size() & 0xff)};
    }
    frame += std::string(4, '\0') + subscribe;
    REQUIRE(::write(fd, frame.data(), frame.size()) == static_cast<ssize_t>(frame.size()));
    return fd;
}

terrain_map_t big_map(int n, int seq)
{
    terrain_map_t m{};
    m.utime = 1'700'000'000'000'000 + seq;
    m.seq = seq;
    m.pose.orientation[0] = 1;
    m.resolution = 0.2f;
    m.nx = m.ny = n;
    m.ncells = n * n;
    for (auto* v : {&m.mean_z, &m.variance_z, &m.max_z, &m.min_z, &m.age_s})
        v->assign(static_cast<std::size_t>(m.ncells), 0.125f * static_cast<float>(seq % 8));
    m.count.assign(static_cast<std::size_t>(m.ncells), seq);
    return m;
}

}  // namespace

TEST_CASE("a client that stops reading: memory bounded, drops counted, nothing encoded unwatched")
{
    test::TempDir dir;
    test::Process bridge({test::bin("ugv-foxglove"), "--config", test::bridge_config(dir, kSlowPort, "client_queue_kb = 256\n"),
                          "--lcm-url", test::lcm_url(kSlowLcm)},
                         dir / "bridge.out", dir / "bridge.err");
    REQUIRE(test::wait_serving(bridge));
    StatusReader status(kSlowLcm);
    lcm::LCM out(test::lcm_url(kSlowLcm));
    constexpr int kCells = 120;  // ~290 kB per LCM message, ~1.3 MB of JSON on its two topics
    const auto publish_maps = [&](int from, int n) {
        for (int k = from; k < from + n; ++k) {
            const terrain_map_t m = big_map(kCells, k);
            out.publish("TERRAIN_MAP", &m);
            std::this_thread::sleep_for(std::chrono::milliseconds(5));
        }
    };

    // No client: the maps' topics are advertised and nothing is encoded.
    publish_maps(0, 3);
    REQUIRE(status.wait([](auto& c) { return c["topics"] >= 2 && c["unwatched"] >= 2; }, 10));
    CHECK(status.counters["encoded"] == 0);

    const int fd = stalled_client(kSlowPort, {"TERRAIN_MAP", "TERRAIN_MAP/grid"});
    REQUIRE(status.wait([](auto& c) { return c["subscriptions"] == 2; }, 10));
    // TCP_NODELAY set on the accepted socket (without it, small messages wait for ACKs).
    CHECK(status.counters.at("socket_errors") == 0);
    publish_maps(3, 30);  // fills the socket and the queue
    std::this_thread::sleep_for(std::chrono::seconds(1));
    const int64_t before_kb = rss_kb(bridge.pid());
    const int64_t encoded_before = status.counters["encoded"];
    publish_maps(33, 300);
    REQUIRE(status.wait([&](auto& c) { return c["encoded"] >= encoded_before + 100 && c["messages_dropped"] >= 100; }, 30));
    std::this_thread::sleep_for(std::chrono::seconds(1));
    const int64_t after_kb = rss_kb(bridge.pid());
    const auto& c = status.counters;
    // ~1.3 MB of JSON per map: what the client was offered after `before` is hundreds of MB.
    const int64_t offered_kb = (c.at("encoded") - encoded_before) / 2 * 1300;
    INFO("RSS " << before_kb << " kB -> " << after_kb << " kB; offered ~" << offered_kb << " kB; encoded "
                << c.at("encoded") << ", sent " << c.at("messages_sent") << ", dropped " << c.at("messages_dropped"));
    std::printf("stalled client: RSS %lld kB -> %lld kB while ~%lld kB were offered; %lld encoded, %lld sent, %lld dropped\n",
                static_cast<long long>(before_kb), static_cast<long long>(after_kb), static_cast<long long>(offered_kb),
                static_cast<long long>(c.at("encoded")), static_cast<long long>(c.at("messages_sent")),
                static_cast<long long>(c.at("messages_dropped")));
    // The bound: two queues of 256 kB, a frame being written and the allocator's slack.
    CHECK(after_kb - before_kb < 48 * 1024);
    CHECK(offered_kb > 4 * 48 * 1024);
    CHECK(c.at("messages_dropped") >= 100);
    CHECK(bridge.running());
    ::close(fd);
    bridge.signal(SIGTERM);
    CHECK(bridge.wait_exit(10) == 0);
}
