// The shared stop signals: SIGTERM sets the flag and makes the pipe readable, without
// SA_RESTART; SIGPIPE is ignored; installing twice keeps one pipe. One test case, because
// the flag cannot be cleared once set (and Catch2 puts its own SIGTERM handler back between
// test cases, so the install happens inside it).
#include <catch2/catch.hpp>

#include <poll.h>

#include <csignal>

#include "ugv/runtime/stop_signals.hpp"

TEST_CASE("stop signals: SIGTERM sets the flag and wakes a poll on the pipe")
{
    REQUIRE(ugv::runtime::stop_signal_fd() == -1);
    const int fd = ugv::runtime::install_stop_signals();
    REQUIRE(fd >= 0);
    CHECK(ugv::runtime::install_stop_signals() == fd);  // twice: the same pipe
    CHECK(ugv::runtime::stop_signal_fd() == fd);

    struct sigaction term{}, pipe{};
    REQUIRE(sigaction(SIGTERM, nullptr, &term) == 0);
    CHECK(term.sa_handler != SIG_DFL);
    CHECK(term.sa_handler != SIG_IGN);
    CHECK((term.sa_flags & SA_RESTART) == 0);
    REQUIRE(sigaction(SIGPIPE, nullptr, &pipe) == 0);
    CHECK(pipe.sa_handler == SIG_IGN);

    pollfd p{fd, POLLIN, 0};
    CHECK(::poll(&p, 1, 0) == 0);
    CHECK_FALSE(ugv::runtime::stop_requested());

    REQUIRE(std::raise(SIGTERM) == 0);
    CHECK(ugv::runtime::stop_requested());
    p.revents = 0;
    CHECK(::poll(&p, 1, 0) == 1);
    CHECK((p.revents & POLLIN) != 0);
}
