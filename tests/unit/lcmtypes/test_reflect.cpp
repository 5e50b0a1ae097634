#include <catch2/catch.hpp>

#include <charconv>
#include <cmath>
#include <map>
#include <set>

#include "ugv/reflect.hpp"
#include "ugv/reflect_message.hpp"
#include "ugv_test/encoded.hpp"
#include "ugv_test/process.hpp"
#include "ugv_test/sample_messages.hpp"

using namespace ugv;

namespace {
// Captures what publish_samples() sends, per channel, through a log.
std::map<std::string, std::vector<uint8_t>> encoded_samples()
{
    test::TempDir dir;
    {
        auto w = bus::open_log_writer(dir / "s.lcm", [] { return int64_t{0}; });
        test::publish_samples(*w);
    }
    std::map<std::string, std::vector<uint8_t>> out;
    auto r = bus::open_log_replay(dir / "s.lcm");
    r->subscribe(".*", [&](const std::string& ch, const uint8_t* d, std::size_t n, int64_t) { out[ch].assign(d, d + n); });
    while (r->handle(0) == bus::HandleResult::handled) {
    }
    return out;
}
}  // namespace

TEST_CASE("every ugv type is known to the reflection, with distinct fingerprints")
{
    const auto types = reflect::all_types();
    REQUIRE(types.size() == 14);
    std::set<int64_t> hashes;
    for (const auto& t : types) hashes.insert(t.hash);
    CHECK(hashes.size() == 14);
}

TEST_CASE("every ugv message prints as JSON with its values")
{
    const auto samples = encoded_samples();
    REQUIRE(samples.size() == 14);
    std::map<std::string, std::string> json;
    for (const auto& [ch, bytes] : samples) {
        std::string type;
        REQUIRE(reflect::to_json(bytes.data(), bytes.size(), type, json[ch]) == reflect::DecodeResult::ok);
        CHECK("SAMPLE_" + type.substr(4) == ch);
    }
    CHECK(json["SAMPLE_laser_scan_t"].rfind("{\"utime\":1000,\"seq\":10,\"sensor_id\":\"front\",", 0) == 0);
    CHECK(json["SAMPLE_laser_scan_t"].find("\"ranges\":[1.25,null],\"flags\":[0,2]") != std::string::npos);
    CHECK(json["SAMPLE_gps_fix_t"].find("\"latitude\":50.25,\"longitude\":-110.5") != std::string::npos);
    CHECK(json["SAMPLE_terrain_map_t"].find("\"pose\":{\"utime\":0,") != std::string::npos);
    CHECK(json["SAMPLE_terrain_map_t"].find("\"count\":[3,0]") != std::string::npos);
    CHECK(json["SAMPLE_daemon_status_t"].find("\"counter_names\":[\"scans\"],\"counter_values\":[375]") != std::string::npos);
    CHECK(json["SAMPLE_raw_bytes_t"].find("\"data\":[2,128,255]") != std::string::npos);
    CHECK(json["SAMPLE_sim_truth_t"].find("\"servo_angle\":0.125") != std::string::npos);
    CHECK(json["SAMPLE_traversability_map_t"].find("\"map_seq\":9,") != std::string::npos);
    CHECK(json["SAMPLE_traversability_map_t"].find("\"cell_class\":[2,0],\"cost\":[1,null]") != std::string::npos);
    CHECK(json["SAMPLE_candidate_arcs_t"].find("\"clear_distance_m\":[4.5,12]") != std::string::npos);
    CHECK(json["SAMPLE_candidate_arcs_t"].find("\"blocked\":[1,0],\"best\":1}") != std::string::npos);
}

TEST_CASE("a decoded message prints as its bytes do")
{
    const auto samples = encoded_samples();
    auto check = [&](auto msg, const std::string& channel) {
        INFO(channel);
        const auto& bytes = samples.at(channel);
        REQUIRE(msg.decode(bytes.data(), 0, static_cast<int>(bytes.size())) == static_cast<int>(bytes.size()));
        std::string type, from_bytes, from_msg = "old text";
        REQUIRE(reflect::to_json(bytes.data(), bytes.size(), type, from_bytes) == reflect::DecodeResult::ok);
        reflect::message_json(msg, from_msg);
        CHECK(from_msg == from_bytes);
    };
    check(terrain_map_t{}, "SAMPLE_terrain_map_t");
    check(traversability_map_t{}, "SAMPLE_traversability_map_t");
    check(laser_scan_t{}, "SAMPLE_laser_scan_t");
    check(daemon_status_t{}, "SAMPLE_daemon_status_t");
}

TEST_CASE("float arrays print as to_chars prints each value, repeated values and all")
{
    // The printer keeps the text of recent floats (a cache keyed by their bits): values that
    // repeat, values that share a slot, and more distinct values than it has slots.
    laser_scan_t scan{};
    scan.sensor_id = "front";
    for (int k = 0; k < 20000; ++k) {
        const float v = k % 3 == 0 ? 0.5f : k % 3 == 1 ? 0.001f * static_cast<float>(k) : -1e-7f * static_cast<float>(k % 97);
        scan.ranges.push_back(k % 11 == 0 ? NAN : v);
        scan.flags.push_back(0);
    }
    scan.ranges.push_back(-1.17549435e-38f);
    scan.ranges.push_back(3.4028235e38f);
    scan.flags.resize(scan.ranges.size());
    scan.nranges = static_cast<int32_t>(scan.ranges.size());
    std::string expected = "\"ranges\":[";
    for (std::size_t k = 0; k < scan.ranges.size(); ++k) {
        if (k > 0) expected += ',';
        char b[32];
        expected += std::isfinite(scan.ranges[k]) ? std::string(b, std::to_chars(b, b + sizeof b, scan.ranges[k]).ptr) : "null";
    }
    expected += "]";
    const auto bytes = test::encoded(scan);
    for (int pass = 0; pass < 2; ++pass) {  // the second with the cache full of them
        std::string type, json;
        REQUIRE(reflect::to_json(bytes.data(), bytes.size(), type, json) == reflect::DecodeResult::ok);
        CHECK(json.find(expected) != std::string::npos);
    }
}

TEST_CASE("truncated, unknown and short inputs are told apart")
{
    const auto samples = encoded_samples();
    const auto& scan = samples.at("SAMPLE_laser_scan_t");
    std::string type, json;
    CHECK(reflect::to_json(scan.data(), scan.size() - 1, type, json) == reflect::DecodeResult::malformed);
    CHECK(type == "ugv.laser_scan_t");
    std::vector<uint8_t> longer = scan;
    longer.push_back(0);
    CHECK(reflect::to_json(longer.data(), longer.size(), type, json) == reflect::DecodeResult::malformed);
    const uint8_t unknown[12] = {1, 2, 3, 4, 5, 6, 7, 8, 0, 0, 0, 0};
    CHECK(reflect::to_json(unknown, sizeof unknown, type, json) == reflect::DecodeResult::unknown_type);
    CHECK(reflect::to_json(unknown, 4, type, json) == reflect::DecodeResult::malformed);
}

TEST_CASE("JSON strings are escaped")
{
    CHECK(reflect::json_quote("a\"b\\c\n\x01") == "\"a\\\"b\\\\c\\n\\u0001\"");
}

TEST_CASE("well_formed catches lengths that would make lcm-gen's decode throw or over-allocate")
{
    const auto samples = encoded_samples();
    for (const auto& [ch, bytes] : samples) {
        INFO(ch);
        CHECK(reflect::well_formed(bytes.data(), bytes.size()));
        CHECK_FALSE(reflect::well_formed(bytes.data(), bytes.size() - 1));
    }
    // laser_scan_t: hash(8) utime(8) seq(8) then the sensor_id string length (int32).
    auto scan = samples.at("SAMPLE_laser_scan_t");
    auto zero_len = scan;
    zero_len[24] = zero_len[25] = zero_len[26] = zero_len[27] = 0;  // a zero string length
    CHECK_FALSE(reflect::well_formed(zero_len.data(), zero_len.size()));
    std::string type, json;
    CHECK(reflect::to_json(zero_len.data(), zero_len.size(), type, json) == reflect::DecodeResult::malformed);
    // nranges sits after sensor_id (4 + 6 bytes) and 5 floats and an int32: make it huge.
    auto huge = scan;
    const std::size_t nranges_at = 24 + 4 + 6 + 5 * 4 + 4;
    huge[nranges_at] = 0x7f;
    CHECK_FALSE(reflect::well_formed(huge.data(), huge.size()));
    huge[nranges_at] = 0xff;  // negative
    CHECK_FALSE(reflect::well_formed(huge.data(), huge.size()));
}

TEST_CASE("typed subscriptions count malformed lengths as decode failures, not handler errors")
{
    test::TempDir dir;
    auto samples = encoded_samples();
    auto bad = samples.at("SAMPLE_laser_scan_t");
    bad[24] = bad[25] = bad[26] = bad[27] = 0;
    {
        auto w = bus::open_log_writer(dir / "bad.lcm", [] { return int64_t{0}; });
        w->publish("LMS_SCAN", bad.data(), bad.size());
        const auto& good = samples.at("SAMPLE_laser_scan_t");
        w->publish("LMS_SCAN", good.data(), good.size());
    }
    auto r = bus::open_log_replay(dir / "bad.lcm");
    int got = 0;
    bus::subscribe<laser_scan_t>(*r, "LMS_SCAN", [&](const std::string&, const laser_scan_t& m, int64_t) {
        CHECK(m.sensor_id == "front");
        ++got;
    });
    while (r->handle(0) == bus::HandleResult::handled) {
    }
    CHECK(got == 1);
    CHECK(r->counters().decode_failures == 1);
    CHECK(r->counters().handler_errors == 0);
}
