// The LCM -> Foxglove mapping: topics per type, schemas from the reflection, the JSON of the
// well-known schemas (a grid's layout against the map it came from), status logs on change.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>

#include "ugv/daemon_status_t.hpp"
#include "ugv/foxglove/topics.hpp"
#include "ugv/pose_t.hpp"
#include "ugv/reflect.hpp"
#include "ugv/reflect_message.hpp"
#include "ugv/terrain_map_t.hpp"
#include "ugv_test/encoded.hpp"

using namespace ugv;
using namespace ugv::foxglove;

namespace {

std::vector<uint8_t> base64_decode(std::string_view s)
{
    auto value = [](char c) -> int {
        if (c >= 'A' && c <= 'Z') return c - 'A';
        if (c >= 'a' && c <= 'z') return c - 'a' + 26;
        if (c >= '0' && c <= '9') return c - '0' + 52;
        return c == '+' ? 62 : c == '/' ? 63 : -1;
    };
    std::vector<uint8_t> out;
    uint32_t acc = 0;
    int bits = 0;
    for (const char c : s) {
        const int v = value(c);
        if (v < 0) break;
        acc = (acc << 6) | static_cast<uint32_t>(v);
        bits += 6;
        if (bits >= 8) {
            bits -= 8;
            out.push_back(static_cast<uint8_t>(acc >> bits));
        }
    }
    return out;
}

// The text of a JSON member's value up to the next ',' or '}' (numbers) or the string.
std::string member(const std::string& json, const std::string& key)
{
    const auto at = json.find("\"" + key + "\":");
    REQUIRE(at != std::string::npos);
    std::size_t from = at + key.size() + 3;
    if (json[from] == '"') return json.substr(from + 1, json.find('"', from + 1) - from - 1);
    return json.substr(from, json.find_first_of(",}", from) - from);
}

}  // namespace

TEST_CASE("every ugv type has a raw topic with a schema naming each field")
{
    for (const auto& t : reflect::all_types()) {
        INFO(t.name);
        const auto topics = topics_for("CH", t.name);
        REQUIRE(!topics.empty());
        CHECK(topics[0].topic == "CH");
        CHECK(topics[0].kind == TopicKind::raw);
        const std::string schema = schema_of(topics[0]);
        for (const auto& f : *reflect::fields_of(t.name)) CHECK(schema.find("\"" + std::string(f.name) + "\":") != std::string::npos);
    }
    CHECK(topics_for("CH", "other.type_t").empty());
    // Nested types are inlined; counted arrays are arrays, fixed ones have their length.
    const std::string pose = lcm_json_schema("ugv.pose_t");
    CHECK(pose.find("\"position\":{\"type\":\"array\",\"items\":{\"type\":[\"number\",\"null\"]},\"minItems\":3,\"maxItems\":3}") !=
          std::string::npos);
    CHECK(lcm_json_schema("ugv.terrain_map_t").find("\"pose\":{\"title\":\"ugv.pose_t\"") != std::string::npos);
}

TEST_CASE("the well-known topics of each type")
{
    auto names = [](std::string_view type) {
        std::vector<std::string> out;
        for (const auto& t : topics_for("X", type)) out.push_back(t.topic + " " + t.schema_name);
        return out;
    };
    CHECK(names("ugv.terrain_map_t") == std::vector<std::string>{"X ugv.terrain_map_t", "X/grid foxglove.Grid"});
    CHECK(names("ugv.pose_t") ==
          std::vector<std::string>{"X ugv.pose_t", "X/tf foxglove.FrameTransform", "X/pose foxglove.PoseInFrame"});
    CHECK(names("ugv.laser_scan_t")[1] == "X/scan foxglove.LaserScan");
    CHECK(names("ugv.point_cloud_t")[1] == "X/cloud foxglove.PointCloud");
    CHECK(names("ugv.gps_fix_t")[1] == "X/fix foxglove.LocationFix");
    CHECK(names("ugv.candidate_arcs_t")[1] == "X/scene foxglove.SceneUpdate");
    CHECK(names("ugv.daemon_status_t")[1] == "X/log foxglove.Log");
    CHECK(names("ugv.traversability_map_t")[1] == "X/grid foxglove.Grid");
    CHECK(names("ugv.imu_t").size() == 1);
}

TEST_CASE("a terrain map as a foxglove.Grid: columns along x, rows along y, every cell's fields")
{
    terrain_map_t m{};
    m.utime = 1'500'000'250'000;
    m.pose.utime = m.utime;
    m.pose.orientation[0] = 1;
    m.pose.position[0] = 10;
    m.resolution = 0.5f;
    m.nx = 3;
    m.ny = 2;
    m.ncells = 6;
    m.origin_x = -1;
    m.origin_y = -0.5f;
    for (int k = 0; k < 6; ++k) {
        m.mean_z.push_back(0.25f * static_cast<float>(k));
        m.variance_z.push_back(0.01f);
        m.count.push_back(k);
        m.max_z.push_back(1.0f + static_cast<float>(k));
        m.min_z.push_back(NAN);
        m.age_s.push_back(0.5f);
    }
    const auto bytes = test::encoded(m);
    const auto topics = topics_for("TERRAIN_MAP", "ugv.terrain_map_t");
    Converter conv;
    std::string json;
    REQUIRE(conv.convert(topics[1], bytes.data(), bytes.size(), json));
    CHECK(member(json, "frame_id") == "world");
    CHECK(member(json, "column_count") == "3");
    CHECK(member(json, "cell_stride") == "24");
    CHECK(member(json, "row_stride") == "72");
    CHECK(member(json, "sec") == "1500000");
    CHECK(member(json, "nsec") == "250000000");
    // The corner cell at the pose plus the origin (no yaw).
    CHECK(json.find("\"position\":{\"x\":9,\"y\":-0.5,\"z\":0}") != std::string::npos);
    const auto cells = base64_decode(member(json, "data"));
    REQUIRE(cells.size() == 6 * 24);
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 2; ++j) {
            const std::size_t at = static_cast<std::size_t>(j * 72 + i * 24);
            float height, max;
            int32_t count;
            std::memcpy(&height, cells.data() + at, 4);
            std::memcpy(&count, cells.data() + at + 8, 4);
            std::memcpy(&max, cells.data() + at + 12, 4);
            CHECK(height == m.mean_z[static_cast<std::size_t>(i * 2 + j)]);
            CHECK(count == i * 2 + j);
            CHECK(max == m.max_z[static_cast<std::size_t>(i * 2 + j)]);
        }
    // The raw topic is ugv-dump's JSON.
    REQUIRE(conv.convert(topics[0], bytes.data(), bytes.size(), json));
    CHECK(json.rfind("{\"utime\":1500000250000,", 0) == 0);
    // Bytes that do not decode: counted, nothing produced.
    CHECK_FALSE(conv.convert(topics[1], bytes.data(), bytes.size() - 1, json));
    CHECK(conv.counters().malformed == 1);
}

TEST_CASE("a pose as the world -> body transform")
{
    pose_t p{};
    p.utime = 2'000'000;
    p.position[0] = 1;
    p.position[1] = 2;
    p.position[2] = 3;
    p.orientation[0] = std::cos(0.25);
    p.orientation[3] = std::sin(0.25);
    const auto bytes = test::encoded(p);
    const auto topics = topics_for("POSE", "ugv.pose_t");
    Converter conv;
    std::string json;
    REQUIRE(conv.convert(topics[1], bytes.data(), bytes.size(), json));
    CHECK(member(json, "parent_frame_id") == "world");
    CHECK(member(json, "child_frame_id") == "body");
    CHECK(json.find("\"translation\":{\"x\":1,\"y\":2,\"z\":3}") != std::string::npos);
    CHECK(std::stod(member(json, "w")) == Approx(std::cos(0.25)));
}

TEST_CASE("daemon status as foxglove.Log only when the state or the error changes")
{
    daemon_status_t s{};
    s.name = "ugv-lms";
    s.instance = "front";
    s.state = daemon_status_t::STATE_RUNNING;
    const auto topics = topics_for("STATUS_LMS", "ugv.daemon_status_t");
    Converter conv;
    std::string json;
    auto convert = [&] {
        const auto b = test::encoded(s);
        return conv.convert(topics[1], b.data(), b.size(), json);
    };
    REQUIRE(convert());
    CHECK(member(json, "message") == "RUNNING");
    CHECK(member(json, "name") == "ugv-lms@front");
    CHECK(member(json, "level") == "2");
    CHECK_FALSE(convert());
    s.state = daemon_status_t::STATE_DEGRADED;
    s.last_error = "no scan for 0.5 s";
    REQUIRE(convert());
    CHECK(member(json, "message") == "DEGRADED: no scan for 0.5 s");
    CHECK(member(json, "level") == "3");
    CHECK_FALSE(convert());
    CHECK(conv.counters().unchanged == 2);
}

TEST_CASE("a map's raw and grid topics from one decode are those from two; the next map is decoded anew")
{
    auto map = [](float base) {
        terrain_map_t m{};
        m.resolution = 0.5f;
        m.nx = 2;
        m.ny = 2;
        m.ncells = 4;
        for (int k = 0; k < 4; ++k) {
            const float v = base + 0.125f * static_cast<float>(k);
            m.mean_z.push_back(v);
            m.variance_z.push_back(v / 8);
            m.count.push_back(k);
            m.max_z.push_back(v + 1);
            m.min_z.push_back(k == 2 ? NAN : v - 1);
            m.age_s.push_back(0.25f);
        }
        return test::encoded(m);
    };
    const auto first = map(1), second = map(-3);
    const auto topics = topics_for("TERRAIN_MAP", "ugv.terrain_map_t");
    // Each topic on its own converter (one decode each): the reference.
    auto alone = [&](const std::vector<uint8_t>& b, std::size_t t) {
        Converter c;
        std::string json;
        REQUIRE(c.convert(topics[t], b.data(), b.size(), json));
        return json;
    };
    Converter conv;
    std::string raw, grid;
    for (const auto* bytes : {&first, &second}) {
        REQUIRE(conv.convert(topics[0], bytes->data(), bytes->size(), raw));
        REQUIRE(conv.convert(topics[1], bytes->data(), bytes->size(), grid, true));
        CHECK(raw == alone(*bytes, 0));
        CHECK(grid == alone(*bytes, 1));
        std::string type, dump;
        REQUIRE(reflect::to_json(bytes->data(), bytes->size(), type, dump) == reflect::DecodeResult::ok);
        CHECK(raw == dump);
    }
}
