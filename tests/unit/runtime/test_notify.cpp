// The sd_notify protocol observed on a unix datagram socket the test binds as NOTIFY_SOCKET.
#include <catch2/catch.hpp>

#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstdlib>

#include "ugv/runtime/notify.hpp"
#include "ugv_test/process.hpp"

namespace {
class NotifySocket
{
public:
    explicit NotifySocket(const std::string& path)
    {
        fd_ = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
        sockaddr_un a{};
        a.sun_family = AF_UNIX;
        std::snprintf(a.sun_path, sizeof a.sun_path, "%s", path.c_str());
        REQUIRE(::bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0);
        setenv("NOTIFY_SOCKET", path.c_str(), 1);
    }
    ~NotifySocket()
    {
        ::close(fd_);
        unsetenv("NOTIFY_SOCKET");
    }
    std::string next(int timeout_ms = 1000)
    {
        pollfd p{fd_, POLLIN, 0};
        if (::poll(&p, 1, timeout_ms) <= 0) return "";
        char buf[512];
        const ssize_t n = ::recv(fd_, buf, sizeof buf, 0);
        return n > 0 ? std::string(buf, static_cast<std::size_t>(n)) : "";
    }

private:
    int fd_ = -1;
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
