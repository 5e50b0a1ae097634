#include "ugv/io/pty.hpp"

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <stdexcept>
#include <unistd.h>

#include "ugv/io/serial_port.hpp"

namespace ugv::io {

Pty::Pty(const std::string& link_path) : link_path_(link_path)
{
    master_ = posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
    if (master_ < 0 || grantpt(master_) != 0 || unlockpt(master_) != 0)
        throw std::runtime_error(std::string("cannot create a pseudo-terminal: ") + std::strerror(errno));
    char name[128];
    if (ptsname_r(master_, name, sizeof name) != 0)
        throw std::runtime_error(std::string("ptsname: ") + std::strerror(errno));
    slave_path_ = name;
    // Hold the slave open ourselves: without it the master reads EIO whenever the daemon
    // has the port closed (between its reconnect attempts).
    slave_keep_ = ::open(name, O_RDWR | O_NOCTTY | O_CLOEXEC);
    if (slave_keep_ < 0) throw std::runtime_error(slave_path_ + ": " + std::strerror(errno));
    // A pty starts in cooked mode; a serial device is raw. The daemon sets its own mode, but
    // until then nothing must be echoed or translated.
    SerialPort raw;
    if (raw.open(slave_path_, 9600)) raw.close();
    if (!link_path_.empty()) {
        ::unlink(link_path_.c_str());
        if (::symlink(slave_path_.c_str(), link_path_.c_str()) != 0)
            throw std::runtime_error(link_path_ + ": cannot link to " + slave_path_ + ": " + std::strerror(errno));
    }
}

Pty::~Pty() { close(); }

int Pty::slave_baud() const { return master_ >= 0 ? get_tty_baud(master_) : -1; }

void Pty::close()
{
    // Unlink once: a new Pty may already own the same link name (device plugged back in).
    if (!link_path_.empty() && master_ >= 0) ::unlink(link_path_.c_str());
    if (slave_keep_ >= 0) ::close(slave_keep_);
    if (master_ >= 0) ::close(master_);
    slave_keep_ = master_ = -1;
}

}  // namespace ugv::io
