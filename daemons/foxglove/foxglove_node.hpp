// The bridge driven by LCM messages: each channel's topics made from its first ugv message
// (lib/foxglove: the same topics, schemas and JSON as ugv-mcap) and advertised to the
// clients; each message encoded only for the topics a client subscribes to, and handed to
// the server's thread.
#pragma once

#include <cstdint>
#include <regex>
#include <string>
#include <unordered_map>
#include <vector>

#include "foxglove_config.hpp"
#include "foxglove_server.hpp"
#include "ugv/daemon/daemon.hpp"
#include "ugv/foxglove/topics.hpp"

namespace ugv::foxglove_daemon {

struct NodeCounters
{
    uint64_t messages_in = 0;     // LCM messages on bridged channels
    uint64_t filtered = 0;        // on channels the `channels` key leaves out
    uint64_t unknown_type = 0;    // not a ugv type (no topic)
    uint64_t malformed = 0;       // a ugv fingerprint whose bytes do not decode, or another type than the channel's
    uint64_t encoded = 0;         // JSON messages made (only for watched topics)
    uint64_t unwatched = 0;       // topic messages not encoded: no client subscribes
    uint64_t channels = 0;        // LCM channels with topics
    uint64_t topics = 0;          // topics advertised
    uint64_t topics_refused = 0;  // topics beyond the server's channel ids (not advertised)

    template <class F>
    void visit(F&& f) const
    {
        f("messages_in", messages_in);
        f("filtered", filtered);
        f("unknown_type", unknown_type);
        f("malformed", malformed);
        f("encoded", encoded);
        f("unwatched", unwatched);
        f("channels", channels);
        f("topics", topics);
        f("topics_refused", topics_refused);
    }
};

class FoxgloveNode
{
public:
    FoxgloveNode(const FoxgloveConfig& config, WsServer& server);

    // One LCM message (recv_utime: the bus's receive time, the messages' log time).
    void on_message(const std::string& channel, const uint8_t* data, std::size_t size, int64_t recv_utime);

    const NodeCounters& counters() const { return counters_; }
    const foxglove::ConverterCounters& converter_counters() const { return converter_.counters(); }

private:
    struct Topic
    {
        foxglove::TopicSpec spec;
        uint32_t id = 0;
    };
    struct Channel
    {
        bool wanted = false;
        std::string type;  // set by the first ugv message
        std::vector<Topic> topics;
    };

    Channel& channel(const std::string& name);
    void make_topics(const std::string& name, std::string_view type, Channel& ch);

    WsServer& server_;
    std::regex channels_, no_raw_;
    std::unordered_map<std::string, Channel> by_name_;
    foxglove::Converter converter_;
    uint32_t next_id_ = 1;
    std::string json_;
    NodeCounters counters_;
};

// The daemon: the server and a FoxgloveNode on the bus until a stop signal.
int run(daemon::Daemon& d, const FoxgloveConfig& config);

}  // namespace ugv::foxglove_daemon
