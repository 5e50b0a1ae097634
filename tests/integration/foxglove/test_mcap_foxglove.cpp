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

#include "sample_log.hpp"
#include "ugv_test/process.hpp"

using namespace ugv;
namespace fs = std::filesystem;

namespace {

[[noreturn]] void skip(const std::string& why)
{
    std::printf("SKIPPED test_mcap_foxglove: %s\n", why.c_str());
    std::fflush(stdout);
    std::exit(77);
}

std::string which(const std::string& program)
{
    const char* path = std::getenv("PATH");
    std::stringstream dirs(path ? path : "");
    for (std::string d; std::getline(dirs, d, ':');) {
        const fs::path p = fs::path(d) / program;
        if (!d.empty() && access(p.c_str(), X_OK) == 0) return p.string();
    }
    return {};
}

// The packages installed in the build folder; the folder with check_mcap.mjs beside them.
const std::string& node_dir()
{
    static const std::string dir = [] {
        const std::string node = which("node"), npm = which("npm");
        if (node.empty() || npm.empty()) skip("no node or npm on the PATH (tools/install-deps installs Debian's)");
        const fs::path src = fs::path(UGV_SOURCE_DIR) / "tests/foxglove";
        const fs::path dst = fs::path(UGV_BINARY_DIR) / "tests/foxglove-node";
        fs::create_directories(dst);
        const bool fresh = fs::exists(dst / "node_modules/@mcap/core") && fs::exists(dst / "package-lock.json") &&
                           test::read_file(dst / "package-lock.json") == test::read_file(src / "package-lock.json");
        for (const char* f : {"package.json", "package-lock.json", "check_mcap.mjs"})
            fs::copy_file(src / f, dst / f, fs::copy_options::overwrite_existing);
        if (!fresh) {
            const std::string log = (dst / "npm-ci.log").string();
            const int rc = test::run({npm, "ci", "--prefix", dst.string(), "--ignore-scripts", "--no-audit", "--no-fund"},
                                     log, log, 180);
            if (rc != 0) skip("npm ci failed (no npm registry?), see " + log);
        }
        return dst.string();
    }();
    return dir;
}

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
    return test::run({which("node"), node_dir() + "/check_mcap.mjs", mcap, expected}, out, out, 120);
}

}  // namespace

TEST_CASE("@mcap/core reads ugv-mcap's file: every topic, the log's counts, valid schemas, the grid")
{
    (void)node_dir();  // skips the whole test where node cannot be had
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
