#include "foxglove_server.hpp"

#include <map>
#include <random>
#include <stdexcept>
#include <thread>
#include <unordered_map>

#include <websocketpp/config/asio_no_tls.hpp>
#include <websocketpp/server.hpp>

namespace ugv::foxglove_daemon {

namespace {

using Endpoint = websocketpp::server<websocketpp::config::asio>;
using Handle = websocketpp::connection_hdl;

struct Client
{
    Endpoint::connection_ptr con;
    std::unordered_map<uint32_t, uint32_t> subscriptions;  // subscription id -> channel id
};

std::string session_id()
{
    std::random_device rd;
    return std::to_string(rd()) + std::to_string(rd());
}

}  // namespace

struct WsServer::Impl
{
    ServerOptions options;
    Endpoint ep;
    std::thread thread;
    bool running = false;
    int port = 0;
    ServerCounters counters;
    // Subscriptions per channel, all clients: written by the server thread, read by publish's caller.
    std::unique_ptr<std::atomic<uint32_t>[]> watchers{new std::atomic<uint32_t>[kMaxChannels + 1]()};
    std::atomic<std::size_t> backlog{0};  // bytes posted by publish(), not yet taken
    const std::string session = session_id();

    // Server thread only.
    std::map<Handle, Client, std::owner_less<Handle>> clients;
    std::vector<ChannelInfo> channels;

    // Within the client's bound too: a client that sends bad operations and never reads the
    // answers must not grow the queue.
    void send_text(const Endpoint::connection_ptr& con, const std::string& text)
    {
        const std::size_t queued = con->get_buffered_amount();
        if (queued > 0 && queued + text.size() > options.client_queue_bytes) {
            ++counters.messages_dropped;
            return;
        }
        (void)con->send(text, websocketpp::frame::opcode::text);
    }

    void refuse_op(const Endpoint::connection_ptr& con, const std::string& why)
    {
        ++counters.client_errors;
        send_text(con, status_json(2, why));
    }

    void unwatch(uint32_t channel_id)
    {
        --watchers[channel_id];
        --counters.subscriptions;
    }

    bool known_channel(uint32_t id) const { return id >= 1 && id <= channels.size(); }

    void on_text(Client& c, const std::string& text)
    {
        const ClientOp op = parse_client_op(text);
        switch (op.kind) {
        case ClientOp::Kind::subscribe:
            for (const auto& s : op.subscriptions) {
                if (!known_channel(s.channel_id)) {
                    refuse_op(c.con, "subscribe: no channel " + std::to_string(s.channel_id));
                } else if (c.subscriptions.count(s.id) != 0) {
                    refuse_op(c.con, "subscribe: subscription id " + std::to_string(s.id) + " is in use");
                } else {
                    c.subscriptions.emplace(s.id, s.channel_id);
                    ++watchers[s.channel_id];
                    ++counters.subscriptions;
                }
            }
            break;
        case ClientOp::Kind::unsubscribe:
            for (uint32_t id : op.unsubscribe_ids) {
                auto it = c.subscriptions.find(id);
                if (it == c.subscriptions.end()) continue;  // the spec lets a client repeat it
                unwatch(it->second);
                c.subscriptions.erase(it);
            }
            break;
        case ClientOp::Kind::other:
            refuse_op(c.con, "\"" + op.op + "\" is not offered by this server (read-only)");
            break;
        case ClientOp::Kind::invalid:
            refuse_op(c.con, "invalid operation: " + op.op);
            break;
        }
    }

    void drop_client(Handle h)
    {
        auto it = clients.find(h);
        if (it == clients.end()) return;
        for (const auto& [sub, channel] : it->second.subscriptions) unwatch(channel);
        clients.erase(it);
        --counters.clients;
    }

    // Server thread: one message to each subscription of its channel, within each client's bound.
    void deliver(uint32_t channel_id, uint64_t log_time_ns, const std::string& payload)
    {
        uint8_t header[kMessageHeaderBytes];
        const std::size_t frame = kMessageHeaderBytes + payload.size();
        for (auto& [h, c] : clients) {
            for (const auto& [sub, channel] : c.subscriptions) {
                if (channel != channel_id) continue;
                // A message always goes to an empty queue, so a message larger than the bound
                // still reaches a client that keeps up.
                const std::size_t queued = c.con->get_buffered_amount();
                if (queued > 0 && queued + frame > options.client_queue_bytes) {
                    ++counters.messages_dropped;
                    continue;
                }
                message_header(sub, log_time_ns, header);
                auto msg = c.con->get_message(websocketpp::frame::opcode::binary, frame);
                std::string& raw = msg->get_raw_payload();
                raw.reserve(frame);
                raw.assign(reinterpret_cast<const char*>(header), kMessageHeaderBytes);
                raw.append(payload);
                if (c.con->send(msg)) {
                    ++counters.client_errors;
                    continue;
                }
                ++counters.messages_sent;
                counters.bytes_sent += frame;
            }
        }
    }
};

WsServer::WsServer(ServerOptions options) : impl_(std::make_unique<Impl>())
{
    impl_->options = std::move(options);
}

WsServer::~WsServer() { stop(); }

void WsServer::start()
{
    Impl& s = *impl_;
    const std::string where = s.options.address + ":" + std::to_string(s.options.port);
    s.ep.clear_access_channels(websocketpp::log::alevel::all);
    s.ep.clear_error_channels(websocketpp::log::elevel::all);
    s.ep.set_max_message_size(1 << 20);  // client operations are small
    std::error_code ec;
    s.ep.init_asio(ec);
    if (ec) throw std::runtime_error(where + ": " + ec.message());
    s.ep.set_reuse_addr(true);
    // Each message out at once: with Nagle, a pose waited for the ACK of the one before, which
    // the client delays (20-40 ms). Set once accepted: the socket-init handler runs before the
    // socket is open.
    s.ep.set_tcp_pre_init_handler([&s](Handle h) {
        std::error_code e;
        s.ep.get_con_from_hdl(h)->get_socket().set_option(asio::ip::tcp::no_delay(true), e);
        if (e) ++s.counters.socket_errors;
    });
    s.ep.set_validate_handler([&s](Handle h) {
        auto con = s.ep.get_con_from_hdl(h);
        bool offered = false;
        for (const auto& p : con->get_requested_subprotocols()) offered = offered || p == kSubprotocol;
        if (!offered || s.clients.size() >= static_cast<std::size_t>(s.options.max_clients)) {
            ++s.counters.clients_refused;
            return false;
        }
        con->select_subprotocol(kSubprotocol);
        return true;
    });
    s.ep.set_open_handler([&s](Handle h) {
        auto con = s.ep.get_con_from_hdl(h);
        s.clients[h].con = con;
        ++s.counters.clients;
        ++s.counters.clients_total;
        s.send_text(con, server_info_json(s.options.name, s.session));
        if (!s.channels.empty()) s.send_text(con, advertise_json(s.channels));
    });
    s.ep.set_close_handler([&s](Handle h) { s.drop_client(h); });
    s.ep.set_fail_handler([&s](Handle h) { s.drop_client(h); });
    s.ep.set_message_handler([&s](Handle h, Endpoint::message_ptr msg) {
        auto it = s.clients.find(h);
        if (it == s.clients.end()) return;
        if (msg->get_opcode() != websocketpp::frame::opcode::text) {
            s.refuse_op(it->second.con, "binary operations are not offered by this server (read-only)");
            return;
        }
        s.on_text(it->second, msg->get_payload());
    });

    const asio::ip::address address = asio::ip::make_address(s.options.address, ec);
    if (ec) throw std::runtime_error(where + ": " + ec.message());
    s.ep.listen(asio::ip::tcp::endpoint(address, static_cast<unsigned short>(s.options.port)), ec);
    if (ec) throw std::runtime_error(where + ": cannot listen: " + ec.message());
    s.ep.start_accept(ec);
    if (ec) throw std::runtime_error(where + ": cannot accept: " + ec.message());
    asio::error_code aec;
    s.port = s.ep.get_local_endpoint(aec).port();
    s.running = true;
    s.thread = std::thread([&s] { s.ep.run(); });
}

void WsServer::stop()
{
    Impl& s = *impl_;
    if (!s.running) return;
    s.running = false;
    asio::post(s.ep.get_io_service(), [&s] {
        std::error_code ec;
        s.ep.stop_listening(ec);
        for (auto& [h, c] : s.clients) s.ep.close(h, websocketpp::close::status::going_away, "shutting down", ec);
    });
    // The closes are given a moment to go out; a client that does not answer is not waited for.
    asio::steady_timer timer(s.ep.get_io_service(), std::chrono::milliseconds(200));
    timer.async_wait([&s](const asio::error_code&) { s.ep.stop(); });
    s.thread.join();
}

int WsServer::port() const { return impl_->port; }

void WsServer::advertise(std::vector<ChannelInfo> channels)
{
    Impl& s = *impl_;
    asio::post(s.ep.get_io_service(), [&s, list = std::move(channels)]() mutable {
        const std::string text = advertise_json(list);
        for (auto& [h, c] : s.clients) s.send_text(c.con, text);
        for (auto& ch : list) s.channels.push_back(std::move(ch));
    });
}

bool WsServer::watched(uint32_t channel_id) const
{
    return channel_id >= 1 && channel_id <= kMaxChannels && impl_->watchers[channel_id].load(std::memory_order_relaxed) > 0;
}

void WsServer::publish(uint32_t channel_id, uint64_t log_time_ns, std::string payload)
{
    Impl& s = *impl_;
    const std::size_t size = payload.size();
    if (s.backlog.load() + size > s.options.backlog_bytes) {
        ++s.counters.backlog_dropped;
        return;
    }
    s.backlog += size;
    asio::post(s.ep.get_io_service(), [&s, channel_id, log_time_ns, size, p = std::move(payload)] {
        s.deliver(channel_id, log_time_ns, p);
        s.backlog -= size;
    });
}

const ServerCounters& WsServer::counters() const { return impl_->counters; }

}  // namespace ugv::foxglove_daemon
