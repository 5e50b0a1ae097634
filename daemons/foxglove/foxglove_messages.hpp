// The Foxglove WebSocket protocol (subprotocol foxglove.websocket.v1) as bytes: the server's
// JSON operations and binary frames, and the client's operations parsed. No sockets.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace ugv::foxglove_daemon {

inline constexpr const char* kSubprotocol = "foxglove.websocket.v1";

// One advertised topic: what the advertise operation lists.
struct ChannelInfo
{
    uint32_t id = 0;
    std::string topic;
    std::string schema_name;
    std::string schema;  // a JSON Schema (schemaEncoding "jsonschema"); messages are JSON
};

// {"op":"serverInfo",...}: the server's name, no capabilities (read-only), json only.
std::string server_info_json(std::string_view name, std::string_view session_id);
// {"op":"advertise","channels":[...]}.
std::string advertise_json(const std::vector<ChannelInfo>& channels);
// {"op":"status","level":L,"message":...}: 0 info, 1 warning, 2 error.
std::string status_json(int level, std::string_view message);

// The messageData frame's header: opcode 0x01, subscription id (u32 LE), log time (u64 LE,
// ns); the message's bytes follow.
inline constexpr std::size_t kMessageHeaderBytes = 13;
void message_header(uint32_t subscription_id, uint64_t log_time_ns, uint8_t out[kMessageHeaderBytes]);

// A client's text operation. Operations this read-only server does not offer are `other`.
struct ClientOp
{
    enum class Kind { subscribe, unsubscribe, other, invalid };
    Kind kind = Kind::invalid;
    std::string op;  // the op's name (other), or why it is invalid
    struct Subscription
    {
        uint32_t id = 0;
        uint32_t channel_id = 0;
    };
    std::vector<Subscription> subscriptions;  // subscribe
    std::vector<uint32_t> unsubscribe_ids;    // unsubscribe
};
ClientOp parse_client_op(std::string_view text);

}  // namespace ugv::foxglove_daemon
