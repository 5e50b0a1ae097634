// Log writing and replay: what is written is read back in order, identically every time.
#include <catch2/catch.hpp>

#include <tuple>

#include "ugv/bus/typed.hpp"
#include "ugv/pose_t.hpp"
#include "ugv_test/process.hpp"

using namespace ugv;

namespace {
using Event = std::tuple<std::string, int64_t, int64_t, double>;  // channel, recv_utime, seq, x

std::vector<Event> replay_all(const std::string& path, const std::string& regex)
{
    auto r = bus::open_log_replay(path);
    std::vector<Event> out;
    bus::subscribe<pose_t>(*r, regex, [&](const std::string& ch, const pose_t& p, int64_t recv) {
        out.emplace_back(ch, recv, p.seq, p.position[0]);
        CHECK(r->now_utime() == recv);
    });
    while (r->handle(0) == bus::HandleResult::handled) {
    }
    return out;
}
}  // namespace

TEST_CASE("log writer stamps events with its clock; replay gives the identical sequence twice")
{
    test::TempDir dir;
    const std::string path = dir / "poses.lcm";
    {
        int64_t clock = 1'000'000;
        auto w = bus::open_log_writer(path, [&] { return clock; });
        for (int k = 0; k < 50; ++k) {
            pose_t p{};
            p.utime = 5'000'000 + k * 100'000;
            p.seq = k;
            p.position[0] = 0.25 * k;
            clock += 100'000;
            REQUIRE(bus::publish(*w, k % 2 ? "POSE" : "POSE_B", p));
            const uint8_t junk[3] = {1, 2, 3};
            REQUIRE(w->publish("POSE", junk, 3));  // a corrupt message in the log
        }
    }
    const auto first = replay_all(path, "POSE.*");
    const auto second = replay_all(path, "POSE.*");
    REQUIRE(first.size() == 50);
    CHECK(first == second);
    for (int k = 0; k < 50; ++k) {
        CHECK(std::get<0>(first[k]) == (k % 2 ? "POSE" : "POSE_B"));
        CHECK(std::get<1>(first[k]) == 1'100'000 + k * 100'000);
        CHECK(std::get<2>(first[k]) == k);
        CHECK(std::get<3>(first[k]) == 0.25 * k);
    }
    CHECK(replay_all(path, "POSE").size() == 25);  // the regex matches whole names only
}

TEST_CASE("replay counts undecodable messages and reaches the end")
{
    test::TempDir dir;
    const std::string path = dir / "bad.lcm";
    {
        auto w = bus::open_log_writer(path, [] { return int64_t{7}; });
        const uint8_t junk[3] = {1, 2, 3};
        REQUIRE(w->publish("POSE", junk, 3));
    }
    auto r = bus::open_log_replay(path);
    int got = 0;
    bus::subscribe<pose_t>(*r, "POSE", [&](const std::string&, const pose_t&, int64_t) { ++got; });
    CHECK(r->handle(0) == bus::HandleResult::handled);
    CHECK(r->handle(0) == bus::HandleResult::end);
    CHECK(got == 0);
    CHECK(r->counters().decode_failures == 1);
}

TEST_CASE("replay of a missing file is refused with the path")
{
    CHECK_THROWS_WITH(bus::open_log_replay("/nonexistent/x.lcm"), "/nonexistent/x.lcm: cannot open as an LCM log");
}
