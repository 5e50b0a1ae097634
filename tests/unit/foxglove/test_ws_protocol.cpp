// ugv-foxglove's protocol bytes (daemons/foxglove/foxglove_messages): the server's operations
// as the Foxglove WebSocket protocol spells them, the messageData header, the client's
// operations parsed and refused.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include "foxglove_messages.hpp"

using namespace ugv::foxglove_daemon;
using nlohmann::json;

TEST_CASE("serverInfo: json encoding, no capabilities")
{
    const json j = json::parse(server_info_json("ugv-foxglove", "42"));
    CHECK(j["op"] == "serverInfo");
    CHECK(j["name"] == "ugv-foxglove");
    CHECK(j["capabilities"] == json::array());
    CHECK(j["supportedEncodings"] == json::array({"json"}));
    CHECK(j["sessionId"] == "42");
}

TEST_CASE("advertise: each channel with encoding json and its JSON Schema, quotes escaped")
{
    const json j = json::parse(advertise_json({{3, "TERRAIN_MAP/grid", "foxglove.Grid", "{\"type\":\"object\"}"},
                                               {4, "A\"B", "ugv.pose_t", "{}"}}));
    CHECK(j["op"] == "advertise");
    REQUIRE(j["channels"].size() == 2);
    const json& c = j["channels"][0];
    CHECK(c["id"] == 3);
    CHECK(c["topic"] == "TERRAIN_MAP/grid");
    CHECK(c["encoding"] == "json");
    CHECK(c["schemaName"] == "foxglove.Grid");
    CHECK(c["schemaEncoding"] == "jsonschema");
    CHECK(c["schema"] == "{\"type\":\"object\"}");
    CHECK(j["channels"][1]["topic"] == "A\"B");
    CHECK(json::parse(advertise_json({}))["channels"] == json::array());
}

TEST_CASE("status: level and message")
{
    const json j = json::parse(status_json(2, "no channel 9"));
    CHECK(j["op"] == "status");
    CHECK(j["level"] == 2);
    CHECK(j["message"] == "no channel 9");
}

TEST_CASE("messageData header: opcode 1, subscription id u32 LE, log time u64 LE")
{
    uint8_t h[kMessageHeaderBytes];
    message_header(0x04030201u, 0x0c0b0a0908070605ull, h);
    const uint8_t want[kMessageHeaderBytes] = {0x01, 0x01, 0x02, 0x03, 0x04, 0x05, 0x06, 0x07, 0x08, 0x09, 0x0a, 0x0b, 0x0c};
    for (std::size_t k = 0; k < kMessageHeaderBytes; ++k) CHECK(h[k] == want[k]);
    message_header(UINT32_MAX, UINT64_MAX, h);
    for (std::size_t k = 1; k < kMessageHeaderBytes; ++k) CHECK(h[k] == 0xff);
}

TEST_CASE("client operations: subscribe and unsubscribe parsed")
{
    const ClientOp s = parse_client_op(R"({"op":"subscribe","subscriptions":[{"id":0,"channelId":3},{"id":7,"channelId":1}]})");
    REQUIRE(s.kind == ClientOp::Kind::subscribe);
    REQUIRE(s.subscriptions.size() == 2);
    CHECK(s.subscriptions[0].id == 0);
    CHECK(s.subscriptions[0].channel_id == 3);
    CHECK(s.subscriptions[1].id == 7);
    const ClientOp u = parse_client_op(R"({"op":"unsubscribe","subscriptionIds":[7,0]})");
    REQUIRE(u.kind == ClientOp::Kind::unsubscribe);
    CHECK(u.unsubscribe_ids == std::vector<uint32_t>{7, 0});
    const ClientOp other = parse_client_op(R"({"op":"advertise","channels":[]})");
    CHECK(other.kind == ClientOp::Kind::other);
    CHECK(other.op == "advertise");
}

TEST_CASE("client operations: malformed ones are invalid, with the reason")
{
    for (const char* text : {"", "[1]", "not json", R"({"op":3})", R"({"subscriptions":[]})",
                             R"({"op":"subscribe"})", R"({"op":"subscribe","subscriptions":[{"id":1}]})",
                             R"({"op":"subscribe","subscriptions":[{"id":-1,"channelId":1}]})",
                             R"({"op":"subscribe","subscriptions":[{"id":1,"channelId":4294967296}]})",
                             R"({"op":"subscribe","subscriptions":[{"id":1.5,"channelId":1}]})",
                             R"({"op":"unsubscribe","subscriptionIds":["1"]})", R"({"op":"unsubscribe"})"}) {
        INFO(text);
        const ClientOp op = parse_client_op(text);
        CHECK(op.kind == ClientOp::Kind::invalid);
        CHECK(!op.op.empty());
    }
}
