// A pseudo-terminal pair for device emulators and tests. The emulator holds the master; the
// daemon opens the slave (or the symlink at link_path) as if it were /dev/ttyUSB0.
//
// The pair keeps its own slave fd open, so the master never sees EIO when the daemon closes
// the port and opens it again. The master can read the line settings the daemon chose
// (slave_baud()), which is how an emulator models a baud mismatch.
#pragma once

#include <string>

namespace ugv::io {

class Pty
{
public:
    // Creates the pair; if link_path is not empty, a symlink to the slave is made there
    // (replacing a stale one). Throws std::runtime_error on failure (start-up only).
    explicit Pty(const std::string& link_path = "");
    ~Pty();
    Pty(const Pty&) = delete;
    Pty& operator=(const Pty&) = delete;

    int master_fd() const { return master_; }
    const std::string& slave_path() const { return slave_path_; }
    // The symlink if one was asked for, else the slave's own path.
    const std::string& path() const { return link_path_.empty() ? slave_path_ : link_path_; }
    // The baud rate the slave side is set to now (what the host chose), -1 on error.
    int slave_baud() const;
    // Closes both sides and removes the link: to the host, the device was unplugged.
    void close();
    bool is_open() const { return master_ >= 0; }

private:
    int master_ = -1;
    int slave_keep_ = -1;
    std::string slave_path_;
    std::string link_path_;
};

}  // namespace ugv::io
