// Hands messages from the device thread to the main thread, which alone touches the bus:
// Daemon::run() gives its bus up when it returns, so a device thread publishing on its own
// would race the shutdown. push() queues and wakes the main loop through an eventfd.
#pragma once

#include <sys/eventfd.h>
#include <unistd.h>

#include <cstdint>
#include <mutex>
#include <stdexcept>
#include <vector>

namespace ugv::lms_daemon {

template <typename... Messages>
class Outbox
{
public:
    Outbox() : fd_(::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC))
    {
        if (fd_ < 0) throw std::runtime_error("eventfd failed");
    }
    ~Outbox() { ::close(fd_); }
    Outbox(const Outbox&) = delete;
    Outbox& operator=(const Outbox&) = delete;

    int fd() const { return fd_; }

    template <typename M>
    void push(M message)
    {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            std::get<std::vector<M>>(queues_).push_back(std::move(message));
        }
        const uint64_t one = 1;
        (void)!::write(fd_, &one, sizeof one);
    }

    // Main thread: everything queued so far, per type in arrival order.
    std::tuple<std::vector<Messages>...> take()
    {
        uint64_t n;
        (void)!::read(fd_, &n, sizeof n);
        std::tuple<std::vector<Messages>...> out;
        std::lock_guard<std::mutex> lock(mutex_);
        out.swap(queues_);
        return out;
    }

private:
    int fd_;
    std::mutex mutex_;
    std::tuple<std::vector<Messages>...> queues_;
};

}  // namespace ugv::lms_daemon
