// ugv-mcap's command line: each input a user can get wrong gives one line and exit 2;
// --channels picks channels. (The file's content is checked by test_mcap_foxglove.)
#include <catch2/catch.hpp>

#include <filesystem>

#include "sample_log.hpp"
#include "ugv_test/process.hpp"

using namespace ugv;

namespace {

int mcap(const test::TempDir& dir, std::vector<std::string> args)
{
    args.insert(args.begin(), test::bin("ugv-mcap"));
    return test::run(args, dir / "o", dir / "e");
}

std::size_t lines(const std::string& s) { return static_cast<std::size_t>(std::count(s.begin(), s.end(), '\n')); }

}  // namespace

TEST_CASE("ugv-mcap: a missing, empty or foreign log, a bad regex, compression or level: one line, exit 2")
{
    test::TempDir dir;
    const std::string log = dir / "run.lcm";
    test::write_sample_log(log);
    CHECK(mcap(dir, {dir / "missing.lcm", dir / "o.mcap"}) == 2);
    CHECK(test::read_file(dir / "e") == "ugv-mcap: " + (dir / "missing.lcm") + ": No such file or directory\n");
    test::write_file(dir / "empty.lcm", "");
    CHECK(mcap(dir, {dir / "empty.lcm", dir / "o.mcap"}) == 2);
    CHECK(test::read_file(dir / "e").find("empty file") != std::string::npos);
    test::write_file(dir / "text.lcm", std::string(5000, 'x'));
    CHECK(mcap(dir, {dir / "text.lcm", dir / "o.mcap"}) == 2);
    CHECK(test::read_file(dir / "e").find("not an LCM log") != std::string::npos);
    CHECK(mcap(dir, {log, dir / "o.mcap", "--channels", "(("}) == 2);
    CHECK(lines(test::read_file(dir / "e")) == 1);
    CHECK(mcap(dir, {log, dir / "o.mcap", "--compression", "gzip"}) == 2);
    CHECK(lines(test::read_file(dir / "e")) == 1);
    for (const char* level : {"23", "-200000", "x"}) {
        CHECK(mcap(dir, {log, dir / "o.mcap", "--zstd-level", level}) == 2);
        CHECK(lines(test::read_file(dir / "e")) == 1);
    }
    CHECK(mcap(dir, {log, dir / "o.mcap", "--compression", "lz4", "--zstd-level", "3"}) == 2);
    CHECK(test::read_file(dir / "e") == "ugv-mcap: --zstd-level is for --compression zstd, not lz4\n");
    CHECK(mcap(dir, {log, dir / "o.mcap", "--no-such-flag"}) == 2);
    CHECK(lines(test::read_file(dir / "e")) == 1);
    REQUIRE(mcap(dir, {log, dir / "fast.mcap", "--zstd-level", "-5", "--quiet"}) == 0);
    CHECK(mcap(dir, {log, dir / "no-such-dir/o.mcap"}) == 2);
    CHECK(test::read_file(dir / "e").find("cannot write") != std::string::npos);
    CHECK_FALSE(std::filesystem::exists(dir / "o.mcap"));
}

TEST_CASE("ugv-mcap: --channels converts only the matching channels; the summary line counts them")
{
    test::TempDir dir;
    const std::string log = dir / "run.lcm";
    const auto counts = test::write_sample_log(log);
    REQUIRE(mcap(dir, {log, dir / "o.mcap", "--channels", "POSE|TERRAIN_MAP"}) == 0);
    const std::string err = test::read_file(dir / "e");
    const int both = counts.at("POSE") + counts.at("TERRAIN_MAP");
    INFO(err);
    CHECK(err.find(": " + std::to_string(both) + " of ") != std::string::npos);
    CHECK(err.find("on 2 channels") != std::string::npos);
    CHECK(std::filesystem::file_size(dir / "o.mcap") > 100);
    // --no-raw: the maps' grids alone, one message per map.
    REQUIRE(mcap(dir, {log, dir / "g.mcap", "--channels", "TERRAIN_MAP", "--no-raw", "TERRAIN_MAP"}) == 0);
    const std::string grids = test::read_file(dir / "e");
    INFO(grids);
    CHECK(grids.find(", " + std::to_string(counts.at("TERRAIN_MAP")) + " messages on 1 channels") != std::string::npos);
    CHECK(mcap(dir, {log, dir / "g.mcap", "--no-raw", "[z-a]"}) == 2);
    REQUIRE(mcap(dir, {log, dir / "q.mcap", "--quiet"}) == 0);
    CHECK(test::read_file(dir / "e").empty());
}
