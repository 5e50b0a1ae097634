// Whole small files: the atomic write and the bounded read of a regular file.
#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "ugv/io/whole_file.hpp"

namespace fs = std::filesystem;
using ugv::io::ReadResult;

namespace {

fs::path fresh_dir()
{
    const fs::path dir = fs::temp_directory_path() / ("ugv_whole_file_" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

}  // namespace

TEST_CASE("whole file: written atomically, read back, no temporary left")
{
    const fs::path dir = fresh_dir();
    const std::string path = (dir / "map.bin").string();
    const std::vector<uint8_t> first{1, 2, 3}, second(5000, 7);
    std::string why;
    REQUIRE(ugv::io::write_file_atomically(path, first.data(), first.size(), why));
    REQUIRE(ugv::io::write_file_atomically(path, second.data(), second.size(), why));
    std::vector<uint8_t> back;
    REQUIRE(ugv::io::read_regular_file(path, 1 << 20, back, why) == ReadResult::ok);
    CHECK(back == second);
    CHECK_FALSE(fs::exists(path + ".tmp"));
    // A folder that is not there: the error names the file, nothing is left behind.
    CHECK_FALSE(ugv::io::write_file_atomically((dir / "no" / "x").string(), first.data(), first.size(), why));
    CHECK(why.find("no/x.tmp") != std::string::npos);
    fs::remove_all(dir);
}

TEST_CASE("whole file: what is not a small regular file is refused unread")
{
    const fs::path dir = fresh_dir();
    std::vector<uint8_t> bytes;
    std::string why;
    CHECK(ugv::io::read_regular_file((dir / "absent").string(), 100, bytes, why) == ReadResult::missing);

    CHECK(ugv::io::read_regular_file(dir.string(), 100, bytes, why) == ReadResult::not_a_file);
    CHECK(why == "is a directory, not a file");

    // A FIFO without a writer: refused at once, not waited on.
    const std::string fifo = (dir / "fifo").string();
    REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
    CHECK(ugv::io::read_regular_file(fifo, 100, bytes, why) == ReadResult::not_a_file);
    CHECK(why == "is a FIFO, not a file");

    CHECK(ugv::io::read_regular_file("/dev/zero", 100, bytes, why) == ReadResult::not_a_file);
    CHECK(why == "is a character device, not a file");
    // A regular file whose size says nothing (0) is read only to the bound.
    CHECK(ugv::io::read_regular_file("/proc/self/maps", 10, bytes, why) == ReadResult::too_large);
    CHECK(why == "has more than 10 bytes");

    const std::string big = (dir / "big").string();
    std::ofstream(big) << std::string(101, 'x');
    CHECK(ugv::io::read_regular_file(big, 100, bytes, why) == ReadResult::too_large);
    CHECK(why == "is 101 bytes, more than 100");
    CHECK(bytes.empty());
    CHECK(ugv::io::read_regular_file(big, 101, bytes, why) == ReadResult::ok);
    CHECK(bytes.size() == 101);
    fs::remove_all(dir);
}
