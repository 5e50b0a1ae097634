// The handler only sets a flag and writes one byte (both async-signal-safe); errno is kept
// so the interrupted code sees its own.
#include "ugv/runtime/stop_signals.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <mutex>

namespace ugv::runtime {
namespace {

static_assert(std::atomic<bool>::is_always_lock_free && std::atomic<int>::is_always_lock_free,
              "read from a signal handler");

std::atomic<bool> g_stop{false};
std::atomic<int> g_read_fd{-1};
std::atomic<int> g_write_fd{-1};

void on_stop_signal(int)
{
    const int saved = errno;
    g_stop.store(true);
    const int fd = g_write_fd.load();
    const char b = 1;
    // A full pipe (many signals) loses nothing: the flag and one pending byte are enough.
    if (fd >= 0) {
        [[maybe_unused]] const ssize_t n = ::write(fd, &b, 1);
    }
    errno = saved;
}

}  // namespace

int install_stop_signals()
{
    static std::once_flag pipe_once;
    std::call_once(pipe_once, [] {
        int p[2];
        if (::pipe2(p, O_CLOEXEC | O_NONBLOCK) != 0) return;
        g_write_fd.store(p[1]);
        g_read_fd.store(p[0]);
    });
    struct sigaction sa{};
    sa.sa_handler = on_stop_signal;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = 0;  // no SA_RESTART: blocking calls return EINTR
    ::sigaction(SIGINT, &sa, nullptr);
    ::sigaction(SIGTERM, &sa, nullptr);
    struct sigaction ignore{};
    ignore.sa_handler = SIG_IGN;
    sigemptyset(&ignore.sa_mask);
    ::sigaction(SIGPIPE, &ignore, nullptr);
    return g_read_fd.load();
}

bool stop_requested() { return g_stop.load(); }

int stop_signal_fd() { return g_read_fd.load(); }

}  // namespace ugv::runtime
