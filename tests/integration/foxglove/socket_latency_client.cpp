// A Foxglove WebSocket client that only times arrivals: for each message of the given topics,
// the latency from its log time (the bridge's LCM receive time) to the moment its last byte
// is read from this client's socket (same host clock). Nothing else runs in its loop, so the
// figure is the bridge's and the socket's, not a client runtime's (node's collector, its
// event loop): tests/bench/foxglove-live.sh prints it beside Foxglove's own client's.
//   ugv-test-foxglove-latency ws://HOST:PORT SECONDS TOPIC...
// Prints one line per topic as watch_live.mjs does; exit 1 when a topic got no message.
#include <time.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <websocketpp/client.hpp>
#include <websocketpp/config/asio_no_tls_client.hpp>

namespace {

using Client = websocketpp::client<websocketpp::config::asio_client>;

int64_t realtime_ns()
{
    timespec ts{};
    clock_gettime(CLOCK_REALTIME, &ts);
    return int64_t{ts.tv_sec} * 1'000'000'000 + ts.tv_nsec;
}

struct Topic
{
    std::vector<double> latencies_ms;
    std::size_t bytes = 0;
};

double quantile(const std::vector<double>& sorted, double p)
{
    return sorted[std::min(sorted.size() - 1, static_cast<std::size_t>(p * static_cast<double>(sorted.size())))];
}

}  // namespace

int main(int argc, char** argv)
{
    if (argc == 2 && std::string(argv[1]) == "--version") {
        std::printf("ugv-test-foxglove-latency %s\n", UGV_VERSION);
        return 0;
    }
    if (argc < 4) {
        std::fprintf(stderr, "usage: %s ws://HOST:PORT SECONDS TOPIC...\n", argv[0]);
        return 2;
    }
    const std::string url = argv[1];
    char* end = nullptr;
    const double seconds = std::strtod(argv[2], &end);
    if (end == argv[2] || *end != '\0' || !(seconds > 0)) {
        std::fprintf(stderr, "ugv-test-foxglove-latency: SECONDS: '%s' is not a positive number\n", argv[2]);
        return 2;
    }
    std::map<std::string, Topic> topics;
    for (int i = 3; i < argc; ++i) topics[argv[i]];
    std::map<uint32_t, Topic*> by_subscription;

    Client client;
    client.clear_access_channels(websocketpp::log::alevel::all);
    client.clear_error_channels(websocketpp::log::elevel::all);
    client.set_max_message_size(64 << 20);
    client.init_asio();
    client.set_message_handler([&](websocketpp::connection_hdl h, Client::message_ptr msg) {
        const int64_t arrived_ns = realtime_ns();
        const std::string& p = msg->get_payload();
        if (msg->get_opcode() == websocketpp::frame::opcode::binary) {
            // messageData: opcode 1, subscription id u32, log time u64 ns, payload (little-endian).
            if (p.size() < 13 || static_cast<uint8_t>(p[0]) != 1) return;
            uint32_t sub = 0;
            uint64_t log_time_ns = 0;
            std::memcpy(&sub, p.data() + 1, 4);
            std::memcpy(&log_time_ns, p.data() + 5, 8);
            auto it = by_subscription.find(sub);
            if (it == by_subscription.end()) return;
            it->second->latencies_ms.push_back(static_cast<double>(arrived_ns - static_cast<int64_t>(log_time_ns)) / 1e6);
            it->second->bytes += p.size() - 13;
            return;
        }
        const auto op = nlohmann::json::parse(p, nullptr, false);
        if (op.is_discarded() || op.value("op", "") != "advertise") return;
        nlohmann::json subscribe = {{"op", "subscribe"}, {"subscriptions", nlohmann::json::array()}};
        for (const auto& channel : op["channels"]) {
            auto t = topics.find(channel.value("topic", ""));
            if (t == topics.end()) continue;
            const auto id = static_cast<uint32_t>(by_subscription.size() + 1);
            by_subscription[id] = &t->second;
            subscribe["subscriptions"].push_back({{"id", id}, {"channelId", channel["id"]}});
        }
        std::error_code ec;
        if (!subscribe["subscriptions"].empty()) client.send(h, subscribe.dump(), websocketpp::frame::opcode::text, ec);
    });
    bool failed = false;
    client.set_fail_handler([&](websocketpp::connection_hdl h) {
        std::fprintf(stderr, "ugv-test-foxglove-latency: %s: %s\n", url.c_str(),
                     client.get_con_from_hdl(h)->get_ec().message().c_str());
        failed = true;
        client.stop();
    });
    std::error_code ec;
    Client::connection_ptr con = client.get_connection(url, ec);
    if (ec) {
        std::fprintf(stderr, "ugv-test-foxglove-latency: %s: %s\n", url.c_str(), ec.message().c_str());
        return 2;
    }
    con->add_subprotocol("foxglove.websocket.v1");
    client.connect(con);
    asio::steady_timer stop(client.get_io_service(), std::chrono::milliseconds(static_cast<int64_t>(seconds * 1000)));
    stop.async_wait([&](const std::error_code&) { client.stop(); });
    client.run();
    if (failed) return 2;

    int missing = 0;
    for (auto& [name, t] : topics) {
        auto& l = t.latencies_ms;
        std::sort(l.begin(), l.end());
        if (l.empty()) {
            std::printf("socket_latency: %s: 0 messages\n", name.c_str());
            ++missing;
            continue;
        }
        std::printf("socket_latency: %s: %zu messages, %.1f MB; latency ms median %.1f, p95 %.1f, p99 %.1f, max %.1f\n",
                    name.c_str(), l.size(), static_cast<double>(t.bytes) / 1e6, quantile(l, 0.5), quantile(l, 0.95),
                    quantile(l, 0.99), l.back());
    }
    return missing == 0 ? 0 : 1;
}
