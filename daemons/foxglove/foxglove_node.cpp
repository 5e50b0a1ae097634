#include "foxglove_node.hpp"

#include <exception>

#include <spdlog/spdlog.h>

#include "ugv/reflect.hpp"
#include "ugv/runtime/counters.hpp"

namespace ugv::foxglove_daemon {

FoxgloveNode::FoxgloveNode(const FoxgloveConfig& config, WsServer& server)
    : server_(server), channels_(config.channels), no_raw_(config.no_raw.empty() ? "$^" : config.no_raw)
{
}

FoxgloveNode::Channel& FoxgloveNode::channel(const std::string& name)
{
    auto it = by_name_.find(name);
    if (it != by_name_.end()) return it->second;
    Channel c;
    c.wanted = std::regex_match(name, channels_);
    return by_name_.emplace(name, std::move(c)).first->second;
}

void FoxgloveNode::make_topics(const std::string& name, std::string_view type, Channel& ch)
{
    ch.type = type;
    const bool raw = !std::regex_match(name, no_raw_);
    std::vector<ChannelInfo> advertised;
    for (auto& spec : foxglove::topics_for(name, type, raw)) {
        if (next_id_ > WsServer::kMaxChannels) {
            ++counters_.topics_refused;
            continue;
        }
        Topic t{std::move(spec), next_id_++};
        advertised.push_back({t.id, t.spec.topic, t.spec.schema_name, foxglove::schema_of(t.spec)});
        ch.topics.push_back(std::move(t));
    }
    ++counters_.channels;
    counters_.topics += advertised.size();
    if (!advertised.empty()) server_.advertise(std::move(advertised));
}

void FoxgloveNode::on_message(const std::string& name, const uint8_t* data, std::size_t size, int64_t recv_utime)
{
    Channel& ch = channel(name);
    if (!ch.wanted) {
        ++counters_.filtered;
        return;
    }
    ++counters_.messages_in;
    const std::string_view type = reflect::type_name_of(data, size);
    if (type.empty()) {
        ++counters_.unknown_type;
        return;
    }
    if (ch.type.empty()) {
        make_topics(name, type, ch);
    } else if (ch.type != type) {
        ++counters_.malformed;
        return;
    }
    const auto log_time_ns = static_cast<uint64_t>(recv_utime < 0 ? 0 : recv_utime) * 1000;
    bool checked = false, same_message = false;  // a map decodes once for all its watched topics
    for (const Topic& t : ch.topics) {
        // Status topics are converted even when unwatched: a Log is made on a change of
        // state, which the converter can only see from every message.
        const bool watched = server_.watched(t.id);
        if (!watched && t.spec.kind != foxglove::TopicKind::status_log) {
            ++counters_.unwatched;
            continue;
        }
        if (!checked) {
            if (!reflect::well_formed(data, size)) {
                ++counters_.malformed;
                return;
            }
            checked = true;
        }
        const bool made = converter_.convert(t.spec, data, size, json_, same_message);
        same_message = true;
        if (!made || !watched) continue;
        ++counters_.encoded;
        server_.publish(t.id, log_time_ns, json_);
    }
}

int run(daemon::Daemon& d, const FoxgloveConfig& config)
{
    WsServer server({.name = d.name(),
                     .address = config.address,
                     .port = config.port,
                     .max_clients = config.max_clients,
                     .client_queue_bytes = config.client_queue_bytes,
                     .backlog_bytes = 4 * config.client_queue_bytes});
    try {
        server.start();
    } catch (const std::exception& e) {
        spdlog::critical("{}", e.what());
        return 2;
    }
    FoxgloveNode node(config, server);
    // Flowing: LCM messages come, other than the daemon's own status (which the bus loops back).
    d.declare_output("LCM messages", config.health_timeout_us);
    const auto sync_counters = [&] {
        runtime::set_all(d.counters(), node.counters());
        runtime::set_all(d.counters(), server.counters());
        // The converter's: its malformed (bytes a topic could not decode) adds to the node's.
        const foxglove::ConverterCounters& conv = node.converter_counters();
        d.counters()["converted"] = static_cast<int64_t>(conv.converted);
        d.counters()["unchanged"] = static_cast<int64_t>(conv.unchanged);
        d.counters()["malformed"] = static_cast<int64_t>(node.counters().malformed + conv.malformed);
    };
    sync_counters();
    d.add_timer(500'000, sync_counters);
    bool ready = false;
    d.bus().subscribe(config.channels, [&](const std::string& channel, const uint8_t* data, std::size_t size,
                                           int64_t recv_utime) {
        node.on_message(channel, data, size, recv_utime);
        if (channel == config.status_channel) return;
        d.mark_output();
        if (!ready) {
            d.ready();
            ready = true;
        }
    });
    spdlog::info("serving {} on ws://{}:{} ({})", config.channels, config.address, server.port(), kSubprotocol);
    d.notify_status("ws://" + config.address + ":" + std::to_string(server.port()));
    const int rc = d.run();
    server.stop();
    sync_counters();
    const auto& c = d.counters();
    spdlog::info("{} messages in, {} encoded, {} sent, {} dropped for slow clients", c.get("messages_in"),
                 c.get("encoded"), c.get("messages_sent"), c.get("messages_dropped"));
    return rc;
}

}  // namespace ugv::foxglove_daemon
