#include "foxglove_messages.hpp"

#include <nlohmann/json.hpp>

namespace ugv::foxglove_daemon {

using nlohmann::json;

std::string server_info_json(std::string_view name, std::string_view session_id)
{
    return json{{"op", "serverInfo"},
                {"name", name},
                {"capabilities", json::array()},
                {"supportedEncodings", json::array({"json"})},
                {"sessionId", session_id}}
        .dump();
}

std::string advertise_json(const std::vector<ChannelInfo>& channels)
{
    json list = json::array();
    for (const auto& c : channels)
        list.push_back({{"id", c.id},
                        {"topic", c.topic},
                        {"encoding", "json"},
                        {"schemaName", c.schema_name},
                        {"schema", c.schema},
                        {"schemaEncoding", "jsonschema"}});
    return json{{"op", "advertise"}, {"channels", std::move(list)}}.dump();
}

std::string status_json(int level, std::string_view message)
{
    return json{{"op", "status"}, {"level", level}, {"message", message}}.dump();
}

void message_header(uint32_t subscription_id, uint64_t log_time_ns, uint8_t out[kMessageHeaderBytes])
{
    out[0] = 0x01;
    for (int k = 0; k < 4; ++k) out[1 + k] = static_cast<uint8_t>(subscription_id >> (8 * k));
    for (int k = 0; k < 8; ++k) out[5 + k] = static_cast<uint8_t>(log_time_ns >> (8 * k));
}

namespace {

bool as_u32(const json& v, uint32_t& out)
{
    if (!v.is_number_integer()) return false;
    const auto n = v.get<int64_t>();
    if (n < 0 || n > static_cast<int64_t>(UINT32_MAX)) return false;
    out = static_cast<uint32_t>(n);
    return true;
}

ClientOp invalid(std::string why)
{
    ClientOp op;
    op.op = std::move(why);
    return op;
}

}  // namespace

ClientOp parse_client_op(std::string_view text)
{
    const json j = json::parse(text, nullptr, false);
    if (j.is_discarded() || !j.is_object()) return invalid("not a JSON object");
    const auto op_it = j.find("op");
    if (op_it == j.end() || !op_it->is_string()) return invalid("no \"op\"");
    ClientOp out;
    out.op = op_it->get<std::string>();
    if (out.op == "subscribe") {
        const auto subs = j.find("subscriptions");
        if (subs == j.end() || !subs->is_array()) return invalid("subscribe without \"subscriptions\"");
        for (const auto& s : *subs) {
            ClientOp::Subscription sub;
            if (!s.is_object() || !s.contains("id") || !s.contains("channelId") || !as_u32(s["id"], sub.id) ||
                !as_u32(s["channelId"], sub.channel_id))
                return invalid("subscribe: each subscription needs an \"id\" and a \"channelId\"");
            out.subscriptions.push_back(sub);
        }
        out.kind = ClientOp::Kind::subscribe;
    } else if (out.op == "unsubscribe") {
        const auto ids = j.find("subscriptionIds");
        if (ids == j.end() || !ids->is_array()) return invalid("unsubscribe without \"subscriptionIds\"");
        for (const auto& v : *ids) {
            uint32_t id = 0;
            if (!as_u32(v, id)) return invalid("unsubscribe: subscription ids are unsigned integers");
            out.unsubscribe_ids.push_back(id);
        }
        out.kind = ClientOp::Kind::unsubscribe;
    } else {
        out.kind = ClientOp::Kind::other;
    }
    return out;
}

}  // namespace ugv::foxglove_daemon
