// Every daemon refuses a config that is not a small regular file, a bad channel regex, a
// channel name LCM cannot publish on and an unsupported baud rate: exit 2 and one line
// `FILE: KEY: why`, at once (a FIFO must not block). Real binaries; nothing is opened
// (each refusal comes before the bus or the device).
#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <string>
#include <vector>

#include "ugv_test/process.hpp"

using namespace ugv;

namespace {

const std::vector<std::string> kDaemons = {"ugv-gps",     "ugv-lms",  "ugv-imu",      "ugv-servo",   "ugv-nodscan",
                                           "ugv-pose",    "ugv-terrain", "ugv-traverse", "ugv-foxglove"};

struct Outcome
{
    int code;
    std::string err;
};

// Generous: each refusal takes milliseconds; a daemon that blocks or runs on shows as -1.
constexpr double kTimeoutS = 15.0;

Outcome run(const test::TempDir& dir, const std::string& daemon, const std::string& config,
            const std::vector<std::string>& extra = {})
{
    std::vector<std::string> argv = {test::bin(daemon), "--config", config, "--lcm-url", test::lcm_url(7730)};
    argv.insert(argv.end(), extra.begin(), extra.end());
    const int code = test::run(argv, dir / "out", dir / "err", kTimeoutS);
    return {code, test::read_file(dir / "err")};
}

// Exit 2, and stderr is exactly one line that starts with `prefix`.
void check_refused(const Outcome& o, const std::string& prefix)
{
    INFO("stderr: " << o.err.substr(0, 500));
    CHECK(o.code == 2);
    CHECK(o.err.rfind(prefix, 0) == 0);
    CHECK(o.err.find('\n') == o.err.size() - 1);
    CHECK(o.err.size() < 300);
}

Outcome run_with(const test::TempDir& dir, const std::string& daemon, const std::string& toml)
{
    test::write_file(dir / "d.toml", toml);
    return run(dir, daemon, dir / "d.toml");
}

}  // namespace

TEST_CASE("every daemon refuses a config that is not a regular file of at most 1 MB, without blocking")
{
    test::TempDir dir;
    REQUIRE(mkfifo((dir / "fifo").c_str(), 0600) == 0);
    test::write_file(dir / "big.toml", std::string(2 << 20, '#'));  // 2 MB of comment
    std::filesystem::create_directory(dir / "conf.d");
    for (const auto& d : kDaemons) {
        INFO(d);
        check_refused(run(dir, d, dir / "conf.d"), dir / "conf.d" + ": -: is a directory, not a file");
        check_refused(run(dir, d, dir / "fifo"), dir / "fifo" + ": -: is a FIFO, not a file");
        check_refused(run(dir, d, "/dev/zero"), "/dev/zero: -: is a character device, not a file");
        check_refused(run(dir, d, "/dev/urandom"), "/dev/urandom: -: is a character device, not a file");
        check_refused(run(dir, d, "/proc/self/mem"), "/proc/self/mem: -: cannot read the file");
        check_refused(run(dir, d, dir / "big.toml"), dir / "big.toml" + ": -: is 2097152 bytes, more than");
        // The control: a regular file with valid channel names is taken (and the effective
        // config printed), so the refusals above are the file's, not the daemon's.
        test::write_file(dir / "ok.toml", "status_channel = \"STATUS_X.front-2\"\n");
        const Outcome ok = run(dir, d, dir / "ok.toml", {"--print-config"});
        CHECK(ok.code == 0);
        CHECK(test::read_file(dir / "out").find("status_channel = 'STATUS_X.front-2'") != std::string::npos);
    }
}

TEST_CASE("every daemon refuses a status channel LCM cannot publish on, naming the key")
{
    test::TempDir dir;
    for (const auto& d : kDaemons) {
        INFO(d);
        const std::string file = dir / "d.toml";
        check_refused(run_with(dir, d, "status_channel = \"\"\n"), file + ": status_channel: must not be empty");
        check_refused(run_with(dir, d, "status_channel = \".*\"\n"), file + ": status_channel: '.*' is not a channel name");
        check_refused(run_with(dir, d, "status_channel = \"" + std::string(64, 'S') + "\"\n"),
                      file + ": status_channel: is 64 characters, more than LCM's 63");
        // 900 kB of name: inside the file limit, refused by length without being repeated.
        check_refused(run_with(dir, d, "status_channel = \"" + std::string(900'000, 'S') + "\"\n"),
                      file + ": status_channel: is 900000 characters");
    }
}

TEST_CASE("every publish channel key is a channel name, every subscribe key a regex that compiles")
{
    test::TempDir dir;
    const std::vector<std::pair<std::string, std::vector<std::string>>> publish = {
        {"ugv-gps", {"channel_fix", "channel_vel", "channel_raw"}},
        {"ugv-lms", {"channel", "raw_channel"}},
        {"ugv-imu", {"channel", "raw_channel"}},
        {"ugv-servo", {"channel"}},
        {"ugv-nodscan", {"channel"}},
        {"ugv-pose", {"channel"}},
        {"ugv-terrain", {"map_channel"}},
        {"ugv-traverse", {"traversability_channel", "arcs_channel"}},
    };
    const std::string file = dir / "d.toml";
    for (const auto& [d, keys] : publish) {
        for (const auto& key : keys) {
            INFO(d << " " << key);
            check_refused(run_with(dir, d, key + " = \"\"\n"), file + ": " + key + ": must not be empty");
            check_refused(run_with(dir, d, key + " = \"POINTS.*\"\n"), file + ": " + key + ": 'POINTS.*' is not a channel name");
            check_refused(run_with(dir, d, key + " = \"" + std::string(70, 'C') + "\"\n"),
                          file + ": " + key + ": is 70 characters, more than LCM's 63");
        }
    }
    const std::vector<std::pair<std::string, std::vector<std::string>>> subscribe = {
        {"ugv-servo", {"command_channel"}},
        {"ugv-nodscan", {"scan_channel", "servo_channel"}},
        {"ugv-pose", {"gps_fix_channel", "gps_velocity_channel", "imu_channel"}},
        {"ugv-terrain", {"points_channel", "pose_channel"}},
        {"ugv-traverse", {"map_channel"}},
        {"ugv-foxglove", {"channels"}},
    };
    for (const auto& [d, keys] : subscribe) {
        for (const auto& key : keys) {
            INFO(d << " " << key);
            // Was an abort (status 134, a core dump) when the bus compiled it.
            check_refused(run_with(dir, d, key + " = \"([\"\n"), file + ": " + key + ": '([' is not a regex");
            check_refused(run_with(dir, d, key + " = \"\"\n"), file + ": " + key + ": must not be empty");
            check_refused(run_with(dir, d, key + " = \"X{1,9999}\"\n"), file + ": " + key + ": 'X{1,9999}': no {n,m}");
            // A pattern is fine where a pattern is expected.
            test::write_file(file, key + " = \"(GPS|IMU)_.*\"\n");
            CHECK(run(dir, d, file, {"--print-config"}).code == 0);
        }
    }
}

TEST_CASE("baud rates outside each device's set are refused, the servo's slcan baud too")
{
    test::TempDir dir;
    const std::string file = dir / "d.toml";
    check_refused(run_with(dir, "ugv-servo", "transport = \"slcan:/dev/null@7\"\n"),
                  file + ": transport: slcan baud 7 is not one of 9600, ");
    check_refused(run_with(dir, "ugv-servo", "transport = \"slcan:/dev/null@115201\"\n"),
                  file + ": transport: slcan baud 115201 is not one of ");
    check_refused(run_with(dir, "ugv-lms", "baud = 57600\n"), file + ": baud: 57600 is not one of 9600, 19200, 38400, 500000");
    check_refused(run_with(dir, "ugv-imu", "baud = 7\n"), file + ": baud: 7 is not one of ");
    check_refused(run_with(dir, "ugv-gps", "baud = 7\n"), file + ": baud: 7 is not one of ");
    check_refused(run_with(dir, "ugv-gps", "com_baud = 7\n"), file + ": com_baud: 7 is not one of ");
    for (const char* ok : {"slcan:/dev/null@115200", "slcan:/dev/null@3000000", "slcan:/dev/null", "socketcan:can0"}) {
        INFO(ok);
        test::write_file(file, std::string("transport = \"") + ok + "\"\n");
        CHECK(run(dir, "ugv-servo", file, {"--print-config"}).code == 0);
    }
}

TEST_CASE("ugv-foxglove refuses each of its own keys set wrong, naming it")
{
    test::TempDir dir;
    const std::string file = dir / "d.toml";
    const auto refused = [&](const std::string& toml, const std::string& why) {
        INFO(toml);
        check_refused(run_with(dir, "ugv-foxglove", toml), file + ": " + why);
    };
    refused("address = \"vehicle\"\n", "address: 'vehicle' is not an IPv4 or IPv6 address");
    refused("address = \"10.0.0.300\"\n", "address: '10.0.0.300' is not an IPv4 or IPv6 address");
    // Neither a second line nor 900 kB echoed into the journal, nor a NUL that would end the text.
    refused("address = \"127.0.0.1\\nX\"\n", "address: a value of 11 characters is not an IPv4 or IPv6 address");
    refused("address = \"127.0.0.1\\u0000junk\"\n", "address: a value of 14 characters is not");
    refused("address = \"" + std::string(900'000, '1') + "\"\n", "address: a value of 900000 characters is not");
    refused("port = 0\n", "port: ");
    refused("port = 65536\n", "port: ");
    refused("port = \"8765\"\n", "port: ");
    refused("max_clients = 0\n", "max_clients: ");
    refused("client_queue_kb = 1\n", "client_queue_kb: ");
    refused("health_timeout_s = nan\n", "health_timeout_s: ");
    // An empty no_raw keeps every raw topic; a non-empty one is a channel regex like `channels`.
    refused("no_raw = \"([\"\n", "no_raw: '([' is not a regex");
    refused("no_raw = \"X{1,9999}\"\n", "no_raw: 'X{1,9999}': no {n,m}");
    refused("no_raw = \"" + std::string(300, 'M') + "\"\n", "no_raw: is 300 characters, more than the 255");
    refused("adress = \"0.0.0.0\"\n", "adress: ");  // a misspelt key is not ignored
    for (const char* ok : {"no_raw = \"\"\n", "no_raw = \"TERRAIN_MAP|TRAVERSABILITY_MAP\"\n", "address = \"::1\"\n",
                           "address = \"0.0.0.0\"\nport = 1\n"}) {
        INFO(ok);
        test::write_file(file, ok);
        CHECK(run(dir, "ugv-foxglove", file, {"--print-config"}).code == 0);
    }
}
