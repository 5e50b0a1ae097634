// lcm-logger (LCM 1.3.1) keeps only what fits liblcm's 30-message subscription queue of what
// arrives while its main loop is not scheduled; with libugv-lcm-queue.so preloaded (as
// ugv-logger.service and tools/lib/stack.sh run it) it keeps every message, also across a
// stop of the whole process.
#include <catch2/catch.hpp>

#include <lcm/lcm.h>
#include <signal.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>

#include "ugv/bus/bus.hpp"
#include "ugv/bus/typed.hpp"
#include "ugv/imu_t.hpp"
#include "ugv_test/process.hpp"

using namespace ugv;

namespace {

constexpr int kMessages = 100;  // 100 small datagrams fit Debian's default 208 kB socket buffer

int count_channel(const std::string& log, const char* channel)
{
    lcm_eventlog_t* l = lcm_eventlog_create(log.c_str(), "r");
    if (l == nullptr) return -1;
    int n = 0;
    while (lcm_eventlog_event_t* e = lcm_eventlog_read_next_event(l)) {
        n += std::strcmp(e->channel, channel) == 0;
        lcm_eventlog_free_event(e);
    }
    lcm_eventlog_destroy(l);
    return n;
}

struct Logged
{
    int messages = 0;
    std::string stderr_text;
};

// Starts lcm-logger (with extra_env), stops it (SIGSTOP), publishes kMessages on QUEUE,
// lets it go on (SIGCONT), stops it cleanly; returns how many QUEUE messages it logged.
Logged logged_across_a_stop(int port, const std::vector<std::string>& extra_env)
{
    test::TempDir dir;
    const std::string url = test::lcm_url(port);
    const std::string log = dir / "run.lcm";
    test::Process logger({"/usr/bin/lcm-logger", "--lcm-url=" + url, "-f", log}, dir / "lo", dir / "le", extra_env);
    REQUIRE(test::wait_until([&] { return std::filesystem::exists(log); }, 10));
    auto bus = bus::open_live(url);
    // lcm-logger subscribes after creating the file: publish until the first arrives.
    REQUIRE(test::wait_until(
        [&] {
            bus::publish(*bus, "PROBE", imu_t{});
            return std::filesystem::file_size(log) > 0;
        },
        10));
    logger.signal(SIGSTOP);
    for (int i = 0; i < kMessages; ++i) {
        imu_t m{};
        m.seq = i;
        bus::publish(*bus, "QUEUE", m);
        usleep(200);
    }
    logger.signal(SIGCONT);
    usleep(1'000'000);
    logger.signal(SIGINT);
    REQUIRE(logger.wait_exit(5) == 0);
    return {count_channel(log, "QUEUE"), logger.err()};
}

}  // namespace

// Why the preload exists, shown without a race: a liblcm subscriber whose main loop does not
// run while a burst arrives keeps 31 of it, every run: the default queue of 30 and one more
// (the 31 lcm-logger kept across a stop, docs/reliability.md). (lcm-logger stopped and resumed
// was the first form of this check, but once resumed its main thread may drain the queue
// as fast as its receive thread fills it, on two cores, and then it dropped nothing.)
TEST_CASE("liblcm keeps 31 messages of a burst for a subscriber that is not handling")
{
    const std::string url = test::lcm_url(7616);
    lcm_t* lcm = lcm_create(url.c_str());
    REQUIRE(lcm != nullptr);
    int received = 0;
    lcm_subscribe(
        lcm, "QUEUE", [](const lcm_recv_buf_t*, const char*, void* n) { ++*static_cast<int*>(n); }, &received);
    auto bus = bus::open_live(url);
    for (int i = 0; i < kMessages; ++i) {
        imu_t m{};
        m.seq = i;
        bus::publish(*bus, "QUEUE", m);
        usleep(200);
    }
    usleep(500'000);  // liblcm's receive thread has taken them all (or dropped them)
    while (lcm_handle_timeout(lcm, 200) > 0) {}
    lcm_destroy(lcm);
    CHECK(received == 31);
}

TEST_CASE("lcm-logger with libugv-lcm-queue.so keeps every message across a stop")
{
    const Logged logged = logged_across_a_stop(7617, {"LD_PRELOAD=" UGV_LCM_QUEUE_LIB});
    CHECK(logged.messages == kMessages);
    CHECK(logged.stderr_text.find("libugv-lcm-queue") == std::string::npos);
}

TEST_CASE("A capacity that is not a count is refused with a message and the default used")
{
    const Logged logged = logged_across_a_stop(7618, {"LD_PRELOAD=" UGV_LCM_QUEUE_LIB, "UGV_LCM_QUEUE_CAPACITY=lots"});
    CHECK(logged.messages == kMessages);
    CHECK(logged.stderr_text.find("libugv-lcm-queue: UGV_LCM_QUEUE_CAPACITY=lots is not a count") != std::string::npos);
}
