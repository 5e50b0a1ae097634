// The WebSocket server of the Foxglove protocol (websocketpp on standalone asio): clients,
// their subscriptions and their bounded send queues. No LCM.
//
// Threads: the server runs its asio loop on a thread of its own; every socket operation,
// every client's state and the advertised list live there. The daemon's main thread (the LCM
// thread) calls advertise(), watched() and publish(), which only post work to that loop or
// read an atomic: it never waits on a socket or on a client. Work posted and not yet taken
// by the server thread is bounded too (backlog_bytes): past it, messages are dropped and
// counted (backlog_dropped).
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "foxglove_messages.hpp"

namespace ugv::foxglove_daemon {

struct ServerOptions
{
    std::string name = "ugv-foxglove";
    std::string address = "127.0.0.1";
    int port = 8765;  // 0: any free port (tests), see port()
    int max_clients = 8;
    std::size_t client_queue_bytes = 8u << 20;
    std::size_t backlog_bytes = 32u << 20;
};

struct ServerCounters
{
    std::atomic<uint64_t> clients{0};           // connected now (a level)
    std::atomic<uint64_t> clients_total{0};     // connections accepted
    std::atomic<uint64_t> clients_refused{0};   // handshakes refused: no foxglove.websocket.v1, or max_clients
    std::atomic<uint64_t> subscriptions{0};     // held now, all clients (a level)
    std::atomic<uint64_t> messages_sent{0};     // messageData frames queued to a client's socket
    std::atomic<uint64_t> bytes_sent{0};        // their bytes
    std::atomic<uint64_t> messages_dropped{0};  // frames not sent: the client's queue was full
    std::atomic<uint64_t> backlog_dropped{0};   // messages the server thread was too far behind to take
    std::atomic<uint64_t> client_errors{0};     // client operations refused (bad JSON, unknown channel, ...)
    std::atomic<uint64_t> socket_errors{0};     // accepted sockets whose TCP_NODELAY could not be set

    template <class F>
    void visit(F&& f) const
    {
        f("clients", clients.load());
        f("clients_total", clients_total.load());
        f("clients_refused", clients_refused.load());
        f("subscriptions", subscriptions.load());
        f("messages_sent", messages_sent.load());
        f("bytes_sent", bytes_sent.load());
        f("messages_dropped", messages_dropped.load());
        f("backlog_dropped", backlog_dropped.load());
        f("client_errors", client_errors.load());
        f("socket_errors", socket_errors.load());
    }
};

class WsServer
{
public:
    // Channel ids run from 1 to kMaxChannels.
    static constexpr uint32_t kMaxChannels = 4096;

    explicit WsServer(ServerOptions options);
    ~WsServer();  // stop()

    // Listens and starts the server thread. Throws std::runtime_error("ADDRESS:PORT: why").
    void start();
    // Closes every client and joins the thread.
    void stop();
    int port() const;  // the port listened on

    // Main thread. New topics, sent to every client now and to each client that comes later.
    void advertise(std::vector<ChannelInfo> channels);
    // Whether a client subscribes to the channel now (so its messages are worth encoding).
    bool watched(uint32_t channel_id) const;
    // The message to every subscription of the channel.
    void publish(uint32_t channel_id, uint64_t log_time_ns, std::string payload);

    const ServerCounters& counters() const;

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

}  // namespace ugv::foxglove_daemon
