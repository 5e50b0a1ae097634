// SIGINT/SIGTERM: the handler only sets a flag and writes a byte to a pipe (both
// async-signal-safe); the main loop polls the pipe's read end and stops.
#include <atomic>
#include <csignal>
#include <fcntl.h>
#include <unistd.h>

#include "ugv/daemon/daemon.hpp"

namespace ugv::daemon {
namespace {

std::atomic<bool> g_stop{false};
int g_pipe[2] = {-1, -1};

void on_signal(int)
{
    g_stop.store(true);
    const char b = 1;
    [[maybe_unused]] const ssize_t n = ::write(g_pipe[1], &b, 1);
}

}  // namespace

int install_stop_signals()
{
    if (g_pipe[0] < 0) {
        if (::pipe2(g_pipe, O_CLOEXEC | O_NONBLOCK) != 0) return -1;
        struct sigaction sa{};
        sa.sa_handler = on_signal;
        sigemptyset(&sa.sa_mask);
        sigaction(SIGINT, &sa, nullptr);
        sigaction(SIGTERM, &sa, nullptr);
        std::signal(SIGPIPE, SIG_IGN);
    }
    return g_pipe[0];
}

bool stop_signal_received() { return g_stop.load(); }

}  // namespace ugv::daemon
