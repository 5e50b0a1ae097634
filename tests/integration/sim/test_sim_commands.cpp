// The emulators share one shape: --help ends with 0, a bad flag with 2 and a line naming it,
// and SIGTERM (the shared stop-signal set-up) ends a running emulator with 0.
#include <catch2/catch.hpp>

#include <csignal>
#include <filesystem>
#include <string>
#include <vector>

#include "ugv_test/process.hpp"

using namespace ugv;

namespace {

struct Emulator
{
    std::string name;
    std::vector<std::string> run_args;  // relative to the temp dir
    std::string ready_path;             // exists once it serves
};

const std::vector<Emulator> kEmulators = {
    {"lms", {"--pty", "dev"}, "dev"},
    {"gps", {"--pty", "dev"}, "dev"},
    {"imu", {"--pty", "dev"}, "dev"},
    {"servo", {"--pty", "dev"}, "dev"},
    {"world", {"--run-dir", "run", "--lcm-url", test::lcm_url(7645)}, "run/ready"},
};

// ugv-sim NAME with its run arguments, paths inside dir.
std::vector<std::string> command(const Emulator& e, const test::TempDir& dir)
{
    std::vector<std::string> argv = {test::bin("ugv-sim"), e.name};
    for (std::size_t i = 0; i < e.run_args.size(); ++i) {
        const bool is_path = i > 0 && (e.run_args[i - 1] == "--pty" || e.run_args[i - 1] == "--run-dir");
        argv.push_back(is_path ? dir / e.run_args[i] : e.run_args[i]);
    }
    return argv;
}

}  // namespace

TEST_CASE("ugv-sim: every emulator parses its command line the same way")
{
    for (const Emulator& e : kEmulators) {
        INFO("ugv-sim " << e.name);
        test::TempDir dir;
        CHECK(test::run({test::bin("ugv-sim"), e.name, "--help"}, dir / "out", dir / "err") == 0);
        CHECK(test::read_file(dir / "out").find("--") != std::string::npos);
        std::vector<std::string> bad = command(e, dir);
        bad.push_back("--no-such-flag");
        CHECK(test::run(bad, dir / "out", dir / "err") == 2);
        CHECK(test::read_file(dir / "err").find("--no-such-flag") != std::string::npos);
        CHECK_FALSE(std::filesystem::exists(dir / e.ready_path));
    }
}

TEST_CASE("ugv-sim: every emulator stops cleanly on SIGTERM")
{
    for (const Emulator& e : kEmulators) {
        INFO("ugv-sim " << e.name);
        test::TempDir dir;
        test::Process p(command(e, dir), dir / "out", dir / "err");
        REQUIRE(test::wait_until([&] { return std::filesystem::exists(dir / e.ready_path) || !p.running(); }, 20));
        REQUIRE(p.running());
        p.signal(SIGTERM);
        CHECK(p.wait_exit(10) == 0);
    }
}
