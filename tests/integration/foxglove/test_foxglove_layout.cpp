// The Foxglove layout the project ships (share/foxglove/ugv-layout.json) is valid JSON in
// Foxglove's layout form, and every topic, field and frame it names is one ugv-mcap (and so
// the bridge: the same lib/foxglove) gives: the topics are read back from ugv-mcap's file of
// the sample log plus a status on each status channel of the shipped configs; the frames are
// lib/foxglove's. A renamed channel, topic suffix or schema field fails here, not in the field.
#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <cstring>
#include <filesystem>
#include <map>
#include <set>
#include <string>

#include "sample_log.hpp"
#include "ugv/daemon_status_t.hpp"
#include "ugv/foxglove/topics.hpp"
#include "ugv/runtime/config.hpp"
#include "ugv_test/encoded.hpp"
#include "ugv_test/process.hpp"

using namespace ugv;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

struct Topic
{
    std::string schema_name;
    json schema;  // the JSON Schema of its messages
};

// Little-endian fields of MCAP records (the format's byte order).
class Reader
{
public:
    Reader(const std::string& bytes, std::size_t at, std::size_t end) : b_(bytes), at_(at), end_(end) {}
    uint64_t uint(int n)
    {
        REQUIRE(at_ + static_cast<std::size_t>(n) <= end_);
        uint64_t v = 0;
        for (int k = n - 1; k >= 0; --k) v = (v << 8) | static_cast<uint8_t>(b_[at_ + static_cast<std::size_t>(k)]);
        at_ += static_cast<std::size_t>(n);
        return v;
    }
    std::string string()
    {
        const auto n = static_cast<std::size_t>(uint(4));
        REQUIRE(at_ + n <= end_);
        std::string s = b_.substr(at_, n);
        at_ += n;
        return s;
    }
    std::size_t at() const { return at_; }

private:
    const std::string& b_;
    std::size_t at_, end_;
};

// The topics of an MCAP file and their schemas, from its summary section (schema records
// 0x03 and channel records 0x04; the footer 0x02 says where the summary starts).
std::map<std::string, Topic> mcap_topics(const std::string& path)
{
    const std::string b = test::read_file(path);
    const std::string magic = "\x89MCAP0\r\n";
    constexpr std::size_t kFooter = 1 + 8 + 8 + 8 + 4;
    REQUIRE(b.size() > 2 * magic.size() + kFooter);
    REQUIRE(b.compare(0, magic.size(), magic) == 0);
    REQUIRE(b.compare(b.size() - magic.size(), magic.size(), magic) == 0);
    const std::size_t footer = b.size() - magic.size() - kFooter;
    Reader f(b, footer, footer + kFooter);
    REQUIRE(f.uint(1) == 0x02);
    REQUIRE(f.uint(8) == kFooter - 9);
    const auto summary = static_cast<std::size_t>(f.uint(8));
    REQUIRE(summary > 0);
    REQUIRE(summary < footer);
    std::map<uint64_t, std::pair<std::string, json>> schemas;
    std::map<std::string, Topic> topics;
    for (std::size_t at = summary; at < footer;) {
        Reader r(b, at, footer);
        const uint64_t op = r.uint(1);
        const auto len = static_cast<std::size_t>(r.uint(8));
        const std::size_t next = r.at() + len;
        REQUIRE(next <= footer);
        Reader c(b, r.at(), next);
        if (op == 0x03) {
            const uint64_t id = c.uint(2);
            std::string name = c.string();
            REQUIRE(c.string() == "jsonschema");
            schemas[id] = {std::move(name), json::parse(c.string())};
        } else if (op == 0x04) {
            (void)c.uint(2);
            const uint64_t schema_id = c.uint(2);
            const std::string topic = c.string();
            REQUIRE(schemas.count(schema_id) == 1);
            topics[topic] = {schemas[schema_id].first, schemas[schema_id].second};
        }
        at = next;
    }
    return topics;
}

// What ugv-mcap makes of the sample log (every ugv type on the stack's channels) and of a
// status on each status channel the shipped configs (systemd/config) give the daemons.
std::map<std::string, Topic> advertised_topics(const test::TempDir& dir)
{
    test::write_sample_log(dir / "run.lcm");
    {
        lcm::LogFile log(dir / "status.lcm", "w");
        int64_t t = 1'700'000'000'000'000;
        for (const auto& e : fs::directory_iterator(std::string(UGV_SOURCE_DIR) + "/systemd/config")) {
            if (e.path().extension() != ".toml") continue;
            runtime::Config cfg = runtime::Config::load(e.path());
            const std::string channel = cfg.get_string("status_channel", "");
            INFO(e.path());
            REQUIRE(!channel.empty());
            daemon_status_t s{};
            s.utime = t;
            s.name = e.path().stem().string();
            s.state = daemon_status_t::STATE_RUNNING;
            test::write_event(log, t += 1000, channel, s);
        }
    }
    std::map<std::string, Topic> all;
    for (const char* log : {"run", "status"}) {
        const std::string mcap = dir / (std::string(log) + ".mcap");
        const int rc = test::run({test::bin("ugv-mcap"), dir / (std::string(log) + ".lcm"), mcap, "--quiet"}, dir / "o", dir / "e");
        INFO(test::read_file(dir / "e"));
        REQUIRE(rc == 0);
        all.merge(mcap_topics(mcap));
    }
    return all;
}

// The leaves of a layout tree: panel ids ("Type!id"), in split nodes `first` and `second`.
void panels_of(const json& node, std::set<std::string>& out)
{
    if (node.is_string()) {
        out.insert(node.get<std::string>());
        return;
    }
    REQUIRE(node.is_object());
    REQUIRE(node.contains("first"));
    REQUIRE(node.contains("second"));
    REQUIRE((node.at("direction") == "row" || node.at("direction") == "column"));
    panels_of(node.at("first"), out);
    panels_of(node.at("second"), out);
}

// A message path `TOPIC.field.field[0]` (Foxglove's syntax; our topics have no '.') names a
// numeric field of the topic's JSON Schema (what Plot and State Transitions draw).
void check_message_path(const std::string& path, const std::map<std::string, Topic>& topics)
{
    INFO("message path " << path);
    const std::size_t dot = path.find('.');
    REQUIRE(dot != std::string::npos);
    const std::string topic = path.substr(0, dot);
    REQUIRE(topics.count(topic) == 1);
    const json* schema = &topics.at(topic).schema;
    std::string rest = path.substr(dot + 1);
    while (!rest.empty()) {
        const std::size_t end = rest.find('.');
        std::string name = rest.substr(0, end);
        rest = end == std::string::npos ? "" : rest.substr(end + 1);
        const bool indexed = name.find('[') != std::string::npos;
        name = name.substr(0, name.find('['));
        INFO("field " << name);
        REQUIRE(schema->contains("properties"));
        REQUIRE(schema->at("properties").contains(name));
        schema = &schema->at("properties").at(name);
        if (indexed) {
            REQUIRE(schema->at("type") == "array");
            schema = &schema->at("items");
        }
    }
    CHECK((schema->at("type") == "number" || schema->at("type") == "integer"));  // a plot draws numbers
}

}  // namespace

TEST_CASE("the shipped Foxglove layout names only topics, fields and frames that ugv-mcap and the bridge give")
{
    const json layout = json::parse(test::read_file(std::string(UGV_SOURCE_DIR) + "/share/foxglove/ugv-layout.json"));
    test::TempDir dir;
    const std::map<std::string, Topic> topics = advertised_topics(dir);
    REQUIRE(topics.count("TERRAIN_MAP/grid") == 1);  // the truth is not empty

    // Foxglove's layout form: panel configs by id and the tree that places them, each panel once.
    REQUIRE(layout.at("configById").is_object());
    for (const char* key : {"globalVariables", "userNodes", "playbackConfig"}) CHECK(layout.at(key).is_object());
    std::set<std::string> placed;
    panels_of(layout.at("layout"), placed);
    std::set<std::string> configured;
    for (const auto& [id, config] : layout.at("configById").items()) configured.insert(id);
    CHECK(placed == configured);

    const std::set<std::string> frames = {foxglove::kWorldFrame, foxglove::kBodyFrame, foxglove::kLaserFrame};
    const auto schema_of = [&](const std::string& topic) {
        INFO("topic " << topic);
        REQUIRE(topics.count(topic) == 1);
        return topics.at(topic).schema_name;
    };
    std::multiset<std::string> shown;  // schema names drawn, by panel type
    for (const auto& [id, config] : layout.at("configById").items()) {
        INFO("panel " << id);
        const std::string type = id.substr(0, id.find('!'));
        if (type == "3D") {
            for (const auto& [topic, settings] : config.at("topics").items()) shown.insert("3D " + schema_of(topic));
            CHECK(frames.count(config.at("followTf").get<std::string>()) == 1);
            for (const auto& [key, settings] : config.at("transforms").items()) {
                INFO(key);
                REQUIRE(key.rfind("frame:", 0) == 0);
                CHECK(frames.count(key.substr(6)) == 1);
            }
            for (const auto& [key, layer] : config.at("layers").items())
                if (layer.contains("frameId")) CHECK(frames.count(layer.at("frameId").get<std::string>()) == 1);
        } else if (type == "map") {
            shown.insert("map " + schema_of(config.at("followTopic").get<std::string>()));
            for (const auto& [topic, color] : config.at("topicColors").items()) shown.insert("map " + schema_of(topic));
        } else if (type == "Plot" || type == "StateTransitions") {
            for (const auto& p : config.at("paths")) {
                const std::string path = p.at("value").get<std::string>();
                check_message_path(path, topics);
                shown.insert(type + " " + schema_of(path.substr(0, path.find('.'))));
            }
        } else if (type == "RosOut") {
            shown.insert("RosOut " + schema_of(config.at("topicToRender").get<std::string>()));
        } else {
            FAIL("a panel type this test does not check: " << type);
        }
    }
    // What the layout is for (issue 28): each kind of data in the panel that draws it.
    for (const char* want : {"3D foxglove.Grid", "3D foxglove.LaserScan", "3D foxglove.PointCloud", "3D foxglove.SceneUpdate",
                             "map foxglove.LocationFix", "Plot foxglove.PoseInFrame", "StateTransitions ugv.daemon_status_t",
                             "RosOut foxglove.Log"}) {
        INFO(want);
        CHECK(shown.count(want) >= 1);
    }
}
