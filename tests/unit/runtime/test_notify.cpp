// The sd_notify protocol observed on a unix datagram socket the test binds as NOTIFY_SOCKET.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cstdlib>

#include "ugv/runtime/notify.hpp"
#include "ugv_test/notify_socket.hpp"
#include "ugv_test/process.hpp"

namespace {
// The shared socket, with NOTIFY_SOCKET pointing at it for this process while it lives.
class NotifySocket : public ugv::test::NotifySocket
{
public:
    explicit NotifySocket(const std::string& path) : ugv::test::NotifySocket(path)
    {
        setenv("NOTIFY_SOCKET", path.c_str(), 1);
    }
    ~NotifySocket() { unsetenv("NOTIFY_SOCKET"); }
};
}  // namespace

TEST_CASE("Notifier sends READY, STATUS, WATCHDOG and STOPPING to NOTIFY_SOCKET")
{
    ugv::test::TempDir dir;
    NotifySocket sock(dir / "notify");
    ugv::runtime::Notifier n;
    n.ready();
    CHECK(sock.next() == "READY=1");
    n.status("streaming 37.5 Hz, 0 crc errors");
    CHECK(sock.next() == "STATUS=streaming 37.5 Hz, 0 crc errors");
    n.watchdog();
    CHECK(sock.next() == "WATCHDOG=1");
    n.stopping();
    CHECK(sock.next() == "STOPPING=1");
}

TEST_CASE("Notifier pings the watchdog at half of WATCHDOG_USEC, and not at all without it")
{
    setenv("WATCHDOG_USEC", "4000000", 1);
    setenv("WATCHDOG_PID", std::to_string(getpid()).c_str(), 1);
    ugv::runtime::Notifier with;
    CHECK(with.watchdog_interval_us() == 2'000'000);
    unsetenv("WATCHDOG_USEC");
    unsetenv("WATCHDOG_PID");
    ugv::runtime::Notifier without;
    CHECK(without.watchdog_interval_us() == 0);
}

TEST_CASE("Notifier is a no-op without systemd")
{
    unsetenv("NOTIFY_SOCKET");
    ugv::runtime::Notifier n;
    CHECK_NOTHROW(n.ready());
    CHECK_NOTHROW(n.stopping());
}
