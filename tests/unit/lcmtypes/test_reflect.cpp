#include <catch2/catch.hpp>

#include <map>
#include <set>

#include "ugv/reflect.hpp"
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
    REQUIRE(types.size() == 12);
    std::set<int64_t> hashes;
    for (const auto& t : types) hashes.insert(t.hash);
    CHECK(hashes.size() == 12);
}

TEST_CASE("every ugv message prints as JSON with its values")
{
    const auto samples = encoded_samples();
    REQUIRE(samples.size() == 12);
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
