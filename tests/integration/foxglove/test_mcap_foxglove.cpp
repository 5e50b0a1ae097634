// ugv-mcap's output read by Foxglove's own MCAP library (@mcap/core, under node) with
// tests/foxglove/check_mcap.mjs: every topic present with the log's message count, every
// schema a valid JSON Schema (ajv) that its messages satisfy, the terrain grids decoded.
// The npm packages come from tests/foxglove/package-lock.json with `npm ci`, into the build
// folder. Where node, npm or the packages cannot be had, the test exits 77 (skipped) and
// says why.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "node_packages.hpp"
#include "sample_log.hpp"
#include "ugv_test/process.hpp"

using namespace ugv;
namespace fs = std::filesystem;

namespace {

std::string expected_json(const std::map<std::string, int>& counts)
{
    std::string j = "{\"counts\":{";
    bool first = true;
    for (const auto& [topic, n] : counts) {
        j += (first ? "\"" : ",\"") + topic + "\":" + std::to_string(n);
        first = false;
    }
    // Three cells of each map, as [i, j, height] (i along x).
    j += "},\"grids\":{\"TERRAIN_MAP/grid\":{\"nx\":" + std::to_string(test::kMapNx) +
         ",\"ny\":" + std::to_string(test::kMapNy) + ",\"cells\":[";
    for (int map = 0; map < counts.at("TERRAIN_MAP"); ++map) {
        j += map == 0 ? "[" : ",[";
        first = true;
        for (const auto& [i, j2] : {std::pair{1, 2}, std::pair{39, 0}, std::pair{5, 29}}) {
            char cell[96];
            std::snprintf(cell, sizeof cell, "%s[%d,%d,%.9g]", first ? "" : ",", i, j2,
                          static_cast<double>(test::map_height(map, i, j2)));
            j += cell;
            first = false;
        }
        j += "]";
    }
    return j + "]}}}";
}

int check(const std::string& mcap, const std::string& expected, const std::string& out)
{
    return test::run({test::which("node"), test::node_dir("test_mcap_foxglove") + "/check_mcap.mjs", mcap, expected}, out, out, 120);
}

}  // namespace

TEST_CASE("@mcap/core reads ugv-mcap's file: every topic, the log's counts, valid schemas, the grid")
{
    (void)test::node_dir("test_mcap_foxglove");  // skips the whole test where node cannot be had
    test::TempDir dir;
    const std::string log = dir / "run.lcm";
    auto counts = test::write_sample_log(log);
    for (const char* compression : {"zstd", "lz4"}) {
        INFO(compression);
        const std::string mcap = dir / (std::string("run-") + compression + ".mcap");
        REQUIRE(test::run({test::bin("ugv-mcap"), log, mcap, "--compression", compression}, dir / "o", dir / "e") == 0);
        test::write_file(dir / "expected.json", expected_json(counts));
        const int rc = check(mcap, dir / "expected.json", dir / "check");
        INFO(test::read_file(dir / "check"));
        CHECK(rc == 0);
        if (rc == 0) std::printf("%s", test::read_file(dir / "check").c_str());
    }
}

TEST_CASE("a log cut short: the MCAP holds every event before the cut, exit 1")
{
    test::TempDir dir;
    const std::string log = dir / "run.lcm";
    test::write_sample_log(log);
    // Cut inside the STATUS_LMS events at the end: count what remains with the sample log's
    // own numbers, less the last status and the foreign message.
    auto counts = test::write_sample_log(dir / "again.lcm");
    const auto size = fs::file_size(log);
    fs::resize_file(log, size - 60);  // the foreign event (~47 bytes) and part of the last status
    counts["STATUS_LMS"] -= 1;
    counts["STATUS_LMS/log"] -= 1;  // the last status was the change back to RUNNING
    const std::string mcap = dir / "cut.mcap";
    REQUIRE(test::run({test::bin("ugv-mcap"), log, mcap}, dir / "o", dir / "e") == 1);
    const std::string err = test::read_file(dir / "e");
    CHECK(err.find("damaged from byte") != std::string::npos);
    test::write_file(dir / "expected.json", expected_json(counts));
    const int rc = check(mcap, dir / "expected.json", dir / "check");
    INFO(test::read_file(dir / "check"));
    CHECK(rc == 0);
}
