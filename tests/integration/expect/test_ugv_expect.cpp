// ugv-expect against real traffic: ugv-test-daemon ticking at 20 Hz on its own LCM port.
#include <catch2/catch.hpp>

#include "ugv_test/process.hpp"

using namespace ugv;

TEST_CASE("ugv-expect passes what holds and fails what does not, in one line")
{
    test::TempDir dir;
    const std::string url = test::lcm_url(7631);
    test::write_file(dir / "d.toml", "period_ms = 50\n");
    test::Process daemon({test::bin("ugv-test-daemon"), "--config", dir / "d.toml", "--lcm-url", url}, dir / "do", dir / "de");
    const auto expect = [&](std::vector<std::string> args) {
        std::vector<std::string> argv = {test::bin("ugv-expect"), "--lcm-url", url, "--channel", "TICK", "--for", "2"};
        argv.insert(argv.end(), args.begin(), args.end());
        const int code = test::run(argv, dir / "o", dir / "e", 30);
        return std::make_pair(code, test::read_file(dir / "o"));
    };
    auto [code, line] = expect({"--rate", "12:30", "--max-gap", "0", "--where", "device == \"test\" && nbytes == 0"});
    INFO(line);
    CHECK(code == 0);
    CHECK(line.rfind("TICK: ", 0) == 0);
    CHECK(line.find("seq gaps 0 (max 0) ok") != std::string::npos);
    CHECK(line.find("-> PASS") != std::string::npos);

    std::tie(code, line) = expect({"--rate", "35:40"});
    INFO(line);
    CHECK(code == 1);
    CHECK(line.find("FAIL -> FAIL") != std::string::npos);

    std::tie(code, line) = expect({"--where", "device == \"lms\""});
    CHECK(code == 1);
    CHECK(line.find("where 'device == \"lms\"': 0/") != std::string::npos);

    const int none = test::run({test::bin("ugv-expect"), "--lcm-url", test::lcm_url(7632), "--channel", "TICK", "--wait", "0.5"},
                               dir / "o", dir / "e", 30);
    CHECK(none == 1);
    CHECK(test::read_file(dir / "o") == "TICK: 0 msgs in 5.0 s, 0.00 Hz -> FAIL (nothing arrived)\n");
    CHECK(test::run({test::bin("ugv-expect"), "--channel", "TICK", "--where", "seq 3"}, dir / "o", dir / "e", 30) == 2);
    CHECK(test::read_file(dir / "e") == "ugv-expect: no comparison (== != < <= > >=) in 'seq 3'\n");
}
