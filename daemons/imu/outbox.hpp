// Messages from the device thread to the main thread, which publishes them; push() queues and
// wakes the main loop through an eventfd. (Daemon::out() would also allow publishing from the
// device thread, as ugv-lms does; this keeps every bus call on one thread.)
#pragma once

#include <sys/eventfd.h>
#include <unistd.h>

#include <cstdint>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include <ugv/imu_t.hpp>
#include <ugv/raw_bytes_t.hpp>

namespace ugv::imu_daemon {

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

    int fd() const { return fd_; }  // readable when something is queued

    // Device thread.
    void push(ugv::imu_t m)
    {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            imu_.push_back(std::move(m));
        }
        wake();
    }
    void push(ugv::raw_bytes_t m)
    {
        {
            std::lock_guard<std::mutex> lock(mutex_);
            raw_.push_back(std::move(m));
        }
        wake();
    }

    // Main thread: takes everything queued, in order per type.
    void take(std::vector<ugv::imu_t>& imu, std::vector<ugv::raw_bytes_t>& raw)
    {
        uint64_t n;
        (void)!::read(fd_, &n, sizeof n);  // reset the eventfd counter
        std::lock_guard<std::mutex> lock(mutex_);
        imu.swap(imu_);
        raw.swap(raw_);
        imu_.clear();
        raw_.clear();
    }

private:
    void wake()
    {
        const uint64_t one = 1;
        (void)!::write(fd_, &one, sizeof one);
    }
    int fd_;
    std::mutex mutex_;
    std::vector<ugv::imu_t> imu_;
    std::vector<ugv::raw_bytes_t> raw_;
};

}  // namespace ugv::imu_daemon
