#include <catch2/catch.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include "ugv/runtime/config.hpp"
#include "ugv_test/process.hpp"

using ugv::runtime::Config;
using ugv::runtime::ConfigError;

namespace {
// The one line a daemon prints for text, or "" when the text is valid for the reader below.
std::string error_of(const std::string& text)
{
    try {
        Config c = Config::parse(text, "/etc/ugv/lms.toml");
        c.get_string("device", "/dev/ttyUSB0");
        c.get_int("baud", 500000, {9600, 19200, 38400, 500000});
        c.get_enum("units", "mm", {"mm", "cm"});
        c.get_double("height_m", 0.87, 0.0, 5.0);
        c.get_bool("publish_raw", false);
        c.get_int("sensor_count", 1, 1, 4);
        c.get_doubles("offset_m", {0, 0, 0}, 3, -10, 10);
        Config mount = c.section("mount");
        mount.get_double("tilt_deg", 0, -90, 90);
        c.finish();
        return "";
    } catch (const ConfigError& e) {
        return e.what();
    }
}
}  // namespace

TEST_CASE("a valid file reads through, and defaults fill the rest")
{
    Config c = Config::parse("device = \"/dev/ugv/lms\"\nheight_m = 1\n[mount]\ntilt_deg = -12.5\n", "x.toml");
    CHECK(c.get_string("device", "") == "/dev/ugv/lms");
    CHECK(c.get_double("height_m", 0.87, 0, 5) == 1.0);  // an integer is a fine number
    CHECK(c.get_int("baud", 500000, {9600, 500000}) == 500000);
    Config m = c.section("mount");
    CHECK(m.get_double("tilt_deg", 0, -90, 90) == -12.5);
    CHECK_NOTHROW(c.finish());
    CHECK(error_of("") == "");
}

TEST_CASE("every kind of config error is one line FILE: KEY: why")
{
    CHECK(error_of("baud = 57600") == "/etc/ugv/lms.toml: baud: 57600 is not one of 9600, 19200, 38400, 500000");
    CHECK(error_of("baud = \"fast\"") == "/etc/ugv/lms.toml: baud: must be an integer, not a string");
    CHECK(error_of("device = 3") == "/etc/ugv/lms.toml: device: must be a string, not an integer");
    CHECK(error_of("units = \"inch\"") == "/etc/ugv/lms.toml: units: \"inch\" is not one of \"mm\", \"cm\"");
    CHECK(error_of("height_m = 7.5") == "/etc/ugv/lms.toml: height_m: 7.5 is out of range [0, 5]");
    CHECK(error_of("height_m = nan") == "/etc/ugv/lms.toml: height_m: must be a finite number");
    CHECK(error_of("height_m = true") == "/etc/ugv/lms.toml: height_m: must be a number, not a boolean");
    CHECK(error_of("publish_raw = 1") == "/etc/ugv/lms.toml: publish_raw: must be true or false, not an integer");
    CHECK(error_of("sensor_count = 9") == "/etc/ugv/lms.toml: sensor_count: 9 is out of range [1, 4]");
    CHECK(error_of("offset_m = [1, 2]") == "/etc/ugv/lms.toml: offset_m: must have 3 elements, not 2");
    CHECK(error_of("offset_m = [1, 2, 30]") == "/etc/ugv/lms.toml: offset_m: element 2 (30) is out of range [-10, 10]");
    CHECK(error_of("devise = \"/dev/ttyS0\"") == "/etc/ugv/lms.toml: devise: unknown key");
    CHECK(error_of("[mount]\ntilt_deg = 100") == "/etc/ugv/lms.toml: mount.tilt_deg: 100 is out of range [-90, 90]");
    CHECK(error_of("[mount]\ntilt = 1") == "/etc/ugv/lms.toml: mount.tilt: unknown key");
    CHECK(error_of("mount = 3") == "/etc/ugv/lms.toml: mount: must be a table ([mount]), not an integer");
    CHECK(error_of("baud = ") == "/etc/ugv/lms.toml: -: Error while parsing key-value pair: encountered end-of-file (line 1, column 8)");
}

TEST_CASE("a missing file is a config error naming the file")
{
    CHECK_THROWS_WITH(Config::load("/nonexistent/ugv.toml"),
                      "/nonexistent/ugv.toml: -: cannot read the file: No such file or directory");
}

TEST_CASE("only a regular file of at most 1 MB is a config: the rest is refused before reading")
{
    ugv::test::TempDir dir;
    const auto error = [](const std::string& path) {
        try {
            (void)Config::load(path);
            return std::string("(loaded)");
        } catch (const ConfigError& e) {
            return std::string(e.what());
        }
    };
    CHECK(error(dir.path().string()) == dir.path().string() + ": -: is a directory, not a file");
    // A FIFO with no writer: refused at once, where reading it would wait for a writer forever.
    REQUIRE(mkfifo((dir / "fifo").c_str(), 0600) == 0);
    CHECK(error(dir / "fifo") == dir / "fifo" + ": -: is a FIFO, not a file");
    CHECK(error("/dev/zero") == "/dev/zero: -: is a character device, not a file");
    CHECK(error("/dev/urandom") == "/dev/urandom: -: is a character device, not a file");
    // A regular file that cannot be read (or that reports a size of 0 and never ends).
    CHECK(error("/proc/self/mem") == "/proc/self/mem: -: cannot read the file: Input/output error");
    ugv::test::write_file(dir / "big.toml", std::string(Config::kMaxFileBytes + 1, '#'));
    CHECK(error(dir / "big.toml") == dir / "big.toml" + ": -: is 1048577 bytes, more than 1048576 (the most a config file may have)");
    // Exactly the limit is fine: a comment, then one key.
    ugv::test::write_file(dir / "full.toml", std::string(Config::kMaxFileBytes - 10, '#') + "\nbaud = 1\n");
    Config full = Config::load(dir / "full.toml");
    CHECK(full.get_int("baud", 0, 0, 9) == 1);
    // A symbolic link to a file is followed; to a directory it is refused like the directory.
    REQUIRE(symlink((dir / "full.toml").c_str(), (dir / "link.toml").c_str()) == 0);
    CHECK_NOTHROW(Config::load(dir / "link.toml"));
    REQUIRE(symlink(dir.path().c_str(), (dir / "dirlink.toml").c_str()) == 0);
    CHECK(error(dir / "dirlink.toml") == dir / "dirlink.toml" + ": -: is a directory, not a file");
}

TEST_CASE("channel names to publish on: letters, digits, '_', '-', '.', 1 to 63 characters")
{
    const auto name = [](const std::string& toml) {
        try {
            Config c = Config::parse(toml, "d.toml");
            return c.get_channel("channel", "POSE");
        } catch (const ConfigError& e) {
            return std::string(e.what());
        }
    };
    CHECK(name("") == "POSE");
    CHECK(name("channel = \"POINTS.front\"") == "POINTS.front");
    CHECK(name("channel = \"SAMPLE_pose_t-2\"") == "SAMPLE_pose_t-2");
    const std::string longest(63, 'A');
    CHECK(name("channel = \"" + longest + "\"") == longest);
    CHECK(name("channel = \"\"") == "d.toml: channel: must not be empty");
    CHECK(name("channel = \"" + longest + "B\"") == "d.toml: channel: is 64 characters, more than LCM's 63");
    CHECK(name("channel = \".*\"") == "d.toml: channel: '.*' is not a channel name (letters, digits, '_', '-', '.')");
    CHECK(name("channel = \"POINTS[12]\"") ==
          "d.toml: channel: 'POINTS[12]' is not a channel name (letters, digits, '_', '-', '.')");
    // A newline or control character is never quoted: the error stays one line.
    CHECK(name("channel = \"A\\nB\"") ==
          "d.toml: channel: a channel name is letters, digits, '_', '-' and '.' (found a space or control character)");
    CHECK(name("channel = \"A B\"").find("found a space") != std::string::npos);
    // 5 MB of name: refused by its length, and the message does not repeat it.
    CHECK(name("channel = \"" + std::string(5'000'000, 'X') + "\"") ==
          "d.toml: channel: is 5000000 characters, more than LCM's 63");
}

TEST_CASE("channel regexes to subscribe with: compile for the live bus and the replay, bounded")
{
    const auto regex = [](const std::string& value) {
        try {
            Config c = Config::parse("points = \"" + value + "\"", "t.toml");
            return c.get_channel_regex("points", "POINTS.*");
        } catch (const ConfigError& e) {
            return std::string(e.what());
        }
    };
    CHECK(regex("POINTS.*") == "POINTS.*");
    CHECK(regex("POINTS\\\\.(front|rear)") == "POINTS\\.(front|rear)");
    CHECK(regex("GPS_FIX") == "GPS_FIX");
    CHECK(regex("") == "t.toml: points: must not be empty");
    CHECK(regex("([") == "t.toml: points: '([' is not a regex: Unmatched [, [^, [:, [., or [=");
    CHECK(regex("IMU(").find("t.toml: points: 'IMU(' is not a regex: ") == 0);
    CHECK(regex("*IMU").find("t.toml: points: '*IMU' is not a regex") == 0);
    CHECK(regex("a{99999}") == "t.toml: points: 'a{99999}': no {n,m} in a channel regex");
    // What would make glibc's regcomp take gigabytes (found by fuzz_config): stacked and
    // deeply nested repetitions. Brackets and escapes hold plain characters.
    CHECK(regex("M" + std::string(30, '+')) ==
          "t.toml: points: 'M" + std::string(30, '+') + "': no quantifier on a quantifier in a channel regex");
    CHECK(regex("A+?").find("no quantifier on a quantifier") != std::string::npos);
    CHECK(regex("((((((M)+)+)+)+)+)+").find("groups nested more than 4 deep") != std::string::npos);
    CHECK(regex("((((M)+)+)+)+") == "((((M)+)+)+)+");
    CHECK(regex("[(+*]+X\\\\++") == "[(+*]+X\\++");
    CHECK(regex("[]A]+_[^]B]*") == "[]A]+_[^]B]*");
    CHECK(regex("A*B+C?(D|E)*") == "A*B+C?(D|E)*");
    // A back reference overflowed std::regex's parser (found by fuzz_config); \d is a digit
    // to one compiler and a 'd' to the other.
    CHECK(regex("(A)\\\\3333333333333333333").find("an escape in a channel regex is for punctuation only") !=
          std::string::npos);
    CHECK(regex("A\\\\d").find("not \\d") != std::string::npos);
    CHECK(regex("A B") == "t.toml: points: a channel regex is printable characters without spaces");
    CHECK(regex(std::string(256, 'A')) == "t.toml: points: is 256 characters, more than the 255 a channel regex may have");
    CHECK(regex(std::string(255, 'A')) == std::string(255, 'A'));
}

TEST_CASE("a file on disk loads, and the effective config prints as TOML with defaults")
{
    ugv::test::TempDir dir;
    ugv::test::write_file(dir / "gps.toml", "baud = 115200\n");
    Config c = Config::load(dir / "gps.toml");
    CHECK(c.file() == dir / "gps.toml");
    c.get_int("baud", 9600, 1200, 921600);
    c.get_string("device", "/dev/ugv/gps");
    const std::string out = c.effective_toml();
    CHECK(out.find("baud = 115200") != std::string::npos);
    CHECK(out.find("device = '/dev/ugv/gps'") != std::string::npos);
    // What --print-config prints reads back to the same values.
    Config again = Config::parse(out);
    CHECK(again.get_int("baud", 0, 0, 1000000) == 115200);
    CHECK(again.get_string("device", "") == "/dev/ugv/gps");
}

TEST_CASE("a daemon's own check of a value gives the same one-line form")
{
    Config c = Config::parse("min_tilt_deg = 10\nmax_tilt_deg = 5\n", "servo.toml");
    const double lo = c.get_double("min_tilt_deg", -30, -90, 90);
    const double hi = c.get_double("max_tilt_deg", 30, -90, 90);
    REQUIRE(lo > hi);
    CHECK_THROWS_WITH(c.fail("max_tilt_deg", "must be greater than min_tilt_deg"),
                      "servo.toml: max_tilt_deg: must be greater than min_tilt_deg");
}

TEST_CASE("arrays of tables read element by element, errors naming the element")
{
    auto message_of = [](auto&& f) -> std::string {
        try {
            f();
        } catch (const ConfigError& e) {
            return e.what();
        }
        return "";
    };
    const std::string text = "[[box]]\nx = 1.0\nh = 0.5\n[[box]]\nx = 2.0\n";
    Config c = Config::parse(text, "scene.toml");
    std::vector<Config> boxes = c.tables("box");
    REQUIRE(boxes.size() == 2);
    CHECK(boxes[0].get_double("x", 0, -10, 10) == 1.0);
    CHECK(boxes[0].get_double("h", 1, 0, 10) == 0.5);
    CHECK(boxes[1].get_double("x", 0, -10, 10) == 2.0);
    CHECK(boxes[1].get_double("h", 1, 0, 10) == 1.0);  // default
    for (Config& b : boxes) b.finish();
    c.finish();
    CHECK(c.effective_toml().find("[[box]]") != std::string::npos);
    CHECK(Config::parse("", "s.toml").tables("box").empty());

    Config bad = Config::parse("[[box]]\nx = 20.0\n[[box]]\nx = 1.0\nwidth = 3\n", "s.toml");
    std::vector<Config> b = bad.tables("box");
    CHECK(message_of([&] { b[0].get_double("x", 0, -10, 10); }) == "s.toml: box[0].x: 20 is out of range [-10, 10]");
    b[1].get_double("x", 0, -10, 10);
    CHECK(message_of([&] { b[1].finish(); }) == "s.toml: box[1].width: unknown key");
    CHECK(message_of([&] { Config::parse("box = 3\n", "s.toml").tables("box"); }) ==
          "s.toml: box: must be an array of tables ([[box]]), not an integer");
}

TEST_CASE("has_tables tells an array of tables from a table, another value or nothing")
{
    Config c = Config::parse("n = 3\n[one]\nx = 1\n[[many]]\nx = 1\n[[many]]\nx = 2\n", "s.toml");
    CHECK(c.has_tables("many"));
    CHECK_FALSE(c.has_tables("one"));
    CHECK_FALSE(c.has_tables("n"));
    CHECK_FALSE(c.has_tables("missing"));
    CHECK(c.has("one"));
}
