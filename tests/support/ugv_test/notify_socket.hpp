// Test support: a unix datagram socket bound where a test points NOTIFY_SOCKET, to watch what
// a daemon (or the Notifier) announces to systemd.
#pragma once

#include <poll.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace ugv::test {

class NotifySocket
{
public:
    explicit NotifySocket(const std::string& path) : path_(path)
    {
        fd_ = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
        sockaddr_un a{};
        a.sun_family = AF_UNIX;
        std::snprintf(a.sun_path, sizeof a.sun_path, "%s", path.c_str());
        if (fd_ < 0 || ::bind(fd_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0)
            throw std::runtime_error("cannot bind a notify socket at " + path);
    }
    ~NotifySocket() { ::close(fd_); }
    NotifySocket(const NotifySocket&) = delete;
    NotifySocket& operator=(const NotifySocket&) = delete;

    const std::string& path() const { return path_; }
    // For a child's environment.
    std::string env() const { return "NOTIFY_SOCKET=" + path_; }

    // The next datagram, or "" when none came within timeout_ms.
    std::string next(int timeout_ms = 1000)
    {
        pollfd p{fd_, POLLIN, 0};
        if (::poll(&p, 1, timeout_ms) <= 0) return "";
        char buf[512];
        const ssize_t n = ::recv(fd_, buf, sizeof buf, 0);
        return n > 0 ? std::string(buf, static_cast<std::size_t>(n)) : "";
    }

    // Waits for a datagram containing what; false on timeout.
    bool wait_for(const std::string& what, double timeout_s)
    {
        const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
        while (std::chrono::steady_clock::now() < end)
            if (next(50).find(what) != std::string::npos) return true;
        return false;
    }

private:
    std::string path_;
    int fd_ = -1;
};

}  // namespace ugv::test
