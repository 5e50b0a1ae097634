#include "ugv/io/serial_port.hpp"

#include <asm/termbits.h>  // termios2, BOTHER: any baud rate, not only the Bxxx constants
#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <thread>
#include <unistd.h>

#include "ugv/io/clock.hpp"

// <asm/termbits.h> and <termios.h> cannot be included together; the few termios calls we
// need go through ioctl with the termios2 structure.

namespace ugv::io {

bool set_tty_baud(int fd, int baud)
{
    if (baud <= 0) return false;
    termios2 t{};
    if (ioctl(fd, TCGETS2, &t) != 0) return false;
    t.c_cflag &= ~static_cast<tcflag_t>(CBAUD | (CBAUD << IBSHIFT));
    t.c_cflag |= BOTHER | (BOTHER << IBSHIFT);
    t.c_ispeed = static_cast<speed_t>(baud);
    t.c_ospeed = static_cast<speed_t>(baud);
    if (ioctl(fd, TCSETS2, &t) != 0) return false;
    termios2 check{};
    return ioctl(fd, TCGETS2, &check) == 0 && static_cast<int>(check.c_ospeed) == baud;
}

int get_tty_baud(int fd)
{
    termios2 t{};
    if (ioctl(fd, TCGETS2, &t) != 0) return -1;
    return static_cast<int>(t.c_ispeed != 0 ? t.c_ispeed : t.c_ospeed);
}

double transmission_time_s(std::size_t n, int baud)
{
    return baud > 0 ? static_cast<double>(n) * 10.0 / baud : 0.0;
}

static bool set_raw_8n1(int fd)
{
    termios2 t{};
    if (ioctl(fd, TCGETS2, &t) != 0) return false;
    t.c_iflag &= ~static_cast<tcflag_t>(IGNBRK | BRKINT | PARMRK | ISTRIP | INLCR | IGNCR | ICRNL | IXON | IXOFF | IXANY);
    t.c_oflag &= ~static_cast<tcflag_t>(OPOST);
    t.c_lflag &= ~static_cast<tcflag_t>(ECHO | ECHONL | ICANON | ISIG | IEXTEN);
    t.c_cflag &= ~static_cast<tcflag_t>(CSIZE | PARENB | CSTOPB | CRTSCTS);
    t.c_cflag |= CS8 | CREAD | CLOCAL;
    t.c_cc[VMIN] = 0;
    t.c_cc[VTIME] = 0;
    return ioctl(fd, TCSETS2, &t) == 0;
}

SerialPort::~SerialPort() { close(); }

bool SerialPort::fail(const std::string& what)
{
    error_ = path_ + ": " + what + ": " + std::strerror(errno);
    return false;
}

bool SerialPort::open(const std::string& path, int baud)
{
    close();
    path_ = path;
    fd_ = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (fd_ < 0) return fail("cannot open");
    if (!set_raw_8n1(fd_)) {
        fail("not a serial port (termios refused)");
        close();
        return false;
    }
    if (!set_baud(baud)) {
        const std::string e = path + ": baud " + std::to_string(baud) + " refused by the driver";
        close();
        error_ = e;
        return false;
    }
    ioctl(fd_, TCFLSH, TCIOFLUSH);
    struct stat st{};
    if (::fstat(fd_, &st) == 0) {
        rdev_ = st.st_rdev;
        ino_ = st.st_ino;
    }
    next_node_check_us_ = monotonic_us() + std::chrono::microseconds(kNodeCheckPeriod).count();
    return true;
}

bool SerialPort::node_present()
{
    if (fd_ < 0) return false;
    struct stat st{};
    if (::stat(path_.c_str(), &st) != 0) {
        if (errno != ENOENT && errno != ENOTDIR) return true;  // cannot tell (EACCES...): the fd decides
        error_ = path_ + ": device node vanished";
        return false;
    }
    if (st.st_rdev != rdev_ || st.st_ino != ino_) {
        error_ = path_ + ": device node replaced by another device";
        return false;
    }
    return true;
}

bool SerialPort::reopen()
{
    const int b = baud_;
    const std::string p = path_;
    return open(p, b);
}

void SerialPort::close()
{
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
}

ReadResult SerialPort::read(uint8_t* buf, std::size_t cap, int timeout_ms)
{
    ReadResult r;
    if (fd_ < 0) {
        r.status = ReadResult::Status::closed;
        return r;
    }
    pollfd p{fd_, POLLIN, 0};
    const int rc = ::poll(&p, 1, timeout_ms);
    r.utime = now_utime();
    if (rc == 0) {
        // Quiet: still the same device? (A replaced node never hangs up the old fd.)
        const int64_t now = monotonic_us();
        if (now >= next_node_check_us_) {
            next_node_check_us_ = now + std::chrono::microseconds(kNodeCheckPeriod).count();
            if (!node_present()) r.status = ReadResult::Status::closed;
        }
        return r;
    }
    if (rc < 0) {
        if (errno == EINTR) return r;
        fail("poll");
        r.status = ReadResult::Status::error;
        return r;
    }
    if ((p.revents & POLLIN) == 0 && (p.revents & (POLLHUP | POLLERR | POLLNVAL)) != 0) {
        errno = EIO;
        fail("device hung up");
        r.status = ReadResult::Status::closed;
        return r;
    }
    const ssize_t n = ::read(fd_, buf, cap);
    if (n > 0) {
        r.status = ReadResult::Status::data;
        r.n = static_cast<std::size_t>(n);
        return r;
    }
    if (n < 0 && (errno == EAGAIN || errno == EINTR)) return r;
    // n == 0 after POLLIN on a tty, or EIO: the other side is gone.
    if (n == 0) errno = EIO;
    fail("device went away");
    r.status = ReadResult::Status::closed;
    return r;
}

bool SerialPort::write(const uint8_t* data, std::size_t n)
{
    if (fd_ < 0) {
        error_ = path_ + ": not open";
        return false;
    }
    const std::size_t step = spacing_.count() > 0 ? 1 : n;
    std::size_t done = 0;
    const int64_t deadline = monotonic_us() + 2'000'000;
    while (done < n) {
        const ssize_t w = ::write(fd_, data + done, std::min(step, n - done));
        if (w > 0) {
            done += static_cast<std::size_t>(w);
            if (spacing_.count() > 0 && done < n) std::this_thread::sleep_for(spacing_);
            continue;
        }
        if (w < 0 && errno != EAGAIN && errno != EINTR) return fail("write");
        if (monotonic_us() > deadline) {
            errno = ETIMEDOUT;
            return fail("write (output blocked)");
        }
        pollfd p{fd_, POLLOUT, 0};
        ::poll(&p, 1, 50);
    }
    return true;
}

bool SerialPort::set_baud(int baud)
{
    if (fd_ < 0 || !set_tty_baud(fd_, baud)) return false;
    baud_ = baud;
    return true;
}

void SerialPort::flush_input()
{
    if (fd_ >= 0) ioctl(fd_, TCFLSH, TCIFLUSH);
}

void SerialPort::drain_output()
{
    if (fd_ >= 0) ioctl(fd_, TCSBRK, 1);  // tcdrain
}

}  // namespace ugv::io
