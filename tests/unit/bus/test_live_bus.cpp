// The live bus on real LCM multicast (ttl=0), each test on its own port.
#include <catch2/catch.hpp>

#include <cmath>
#include <stdexcept>

#include "ugv/bus/typed.hpp"
#include "ugv/imu_t.hpp"
#include "ugv/laser_scan_t.hpp"
#include "ugv_test/process.hpp"

using namespace ugv;

namespace {
void pump(bus::Bus& b, int times)
{
    for (int k = 0; k < times; ++k) b.handle(20);
}
}  // namespace

TEST_CASE("live bus: typed publish reaches a typed subscriber with every field intact")
{
    auto a = bus::open_live(test::lcm_url(7601));
    auto b = bus::open_live(test::lcm_url(7601));
    std::vector<laser_scan_t> got;
    std::vector<std::string> channels;
    bus::subscribe<laser_scan_t>(*b, "LMS_SCAN.*", [&](const std::string& ch, const laser_scan_t& m, int64_t recv) {
        CHECK(recv > 0);
        channels.push_back(ch);
        got.push_back(m);
    });
    laser_scan_t s{};
    s.utime = 1'700'000'000'000'000;
    s.seq = 41;
    s.sensor_id = "front";
    s.angle_min = static_cast<float>(-M_PI / 2);
    s.angle_increment = static_cast<float>(M_PI / 360);
    s.nranges = 3;
    s.ranges = {1.5f, NAN, 80.0f};
    s.flags = {laser_scan_t::FLAG_OK, laser_scan_t::FLAG_DAZZLE, laser_scan_t::FLAG_OK};
    REQUIRE(bus::publish(*a, "LMS_SCAN_FRONT", s));
    REQUIRE(bus::publish(*a, "OTHER", s));  // not subscribed
    REQUIRE(test::wait_until([&] { pump(*b, 1); return !got.empty(); }, 5.0));
    pump(*b, 5);
    REQUIRE(got.size() == 1);
    CHECK(channels[0] == "LMS_SCAN_FRONT");
    CHECK(got[0].seq == 41);
    CHECK(got[0].sensor_id == "front");
    CHECK(got[0].ranges[0] == 1.5f);
    CHECK(std::isnan(got[0].ranges[1]));
    CHECK(got[0].flags[1] == laser_scan_t::FLAG_DAZZLE);
}

TEST_CASE("live bus: a publisher that subscribes to nothing has no receive socket to poll")
{
    auto a = bus::open_live(test::lcm_url(7604));
    CHECK(a->fd() == -1);  // so a device daemon's loop never wakes for other daemons' traffic
    bus::subscribe<imu_t>(*a, "IMU", [](const std::string&, const imu_t&, int64_t) {});
    CHECK(a->fd() >= 0);
}

TEST_CASE("live bus: bytes that do not decode as the type are counted and dropped")
{
    auto a = bus::open_live(test::lcm_url(7602));
    auto b = bus::open_live(test::lcm_url(7602));
    int good = 0;
    bus::subscribe<imu_t>(*b, "IMU", [&](const std::string&, const imu_t&, int64_t) { ++good; });
    const uint8_t junk[] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11};
    REQUIRE(a->publish("IMU", junk, sizeof junk));
    laser_scan_t wrong_type{};
    REQUIRE(bus::publish(*a, "IMU", wrong_type));
    imu_t ok{};
    REQUIRE(bus::publish(*a, "IMU", ok));
    REQUIRE(test::wait_until([&] { pump(*b, 1); return good == 1; }, 5.0));
    pump(*b, 5);
    CHECK(good == 1);
    CHECK(b->counters().decode_failures == 2);
}

TEST_CASE("live bus: a handler's exception is caught and counted, never thrown through LCM")
{
    auto a = bus::open_live(test::lcm_url(7603));
    auto b = bus::open_live(test::lcm_url(7603));
    int calls = 0;
    b->subscribe("X", [&](const std::string&, const uint8_t*, std::size_t, int64_t) {
        ++calls;
        throw std::runtime_error("boom");
    });
    const uint8_t one = 1;
    REQUIRE(a->publish("X", &one, 1));
    REQUIRE(a->publish("X", &one, 1));
    REQUIRE(test::wait_until([&] { pump(*b, 1); return calls == 2; }, 5.0));
    CHECK(b->counters().handler_errors == 2);
}

TEST_CASE("live bus: a bad URL is refused with a one-line reason")
{
    CHECK_THROWS_WITH(bus::open_live("nonsense://x"),
                      "LCM cannot be created for 'nonsense://x' (bad URL, or no multicast route?)");
}

TEST_CASE("default URL: LCM_DEFAULT_URL, else udpm with ttl=0")
{
    unsetenv("LCM_DEFAULT_URL");
    CHECK(bus::default_url() == "udpm://239.255.76.67:7667?ttl=0");
    setenv("LCM_DEFAULT_URL", "udpm://239.255.76.67:7777?ttl=1", 1);
    CHECK(bus::default_url() == "udpm://239.255.76.67:7777?ttl=1");
    unsetenv("LCM_DEFAULT_URL");
}
