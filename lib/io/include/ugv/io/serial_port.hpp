// A serial port on termios: raw 8N1, any baud rate (standard ones and others such as
// 500000 through termios2/BOTHER), non-blocking reads with poll() and a receive time stamp
// per chunk, writes with optional inter-byte spacing, reopen after hang-up or EIO.
//
// The device is gone -- read() says `closed` -- only when the port says so (EIO, hang-up,
// POLLERR/POLLNVAL) or when its node vanished or now names another device (a USB adapter
// unplugged behind a udev symlink, an emulator's pty replaced), never because it is quiet:
// a silent device is still there, and a reopen would drop the bytes it sends next.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <sys/types.h>

#include "ugv/io/byte_stream.hpp"

namespace ugv::io {

class SerialPort final : public ByteStream
{
public:
    SerialPort() = default;
    ~SerialPort() override;
    SerialPort(const SerialPort&) = delete;
    SerialPort& operator=(const SerialPort&) = delete;

    // Opens path raw 8N1 at baud, without becoming its controlling terminal. False on
    // failure, with last_error() saying why in one line ("/dev/ttyUSB0: No such file ...").
    bool open(const std::string& path, int baud);
    // Closes and opens again the last path at the current baud (after a hang-up or EIO).
    bool reopen();
    void close();
    bool is_open() const { return fd_ >= 0; }
    int fd() const { return fd_; }
    const std::string& path() const { return path_; }

    // False (with last_error() saying why) when the node at path() vanished or is no longer
    // the device this port has open (compares st_rdev and st_ino). read() checks this itself
    // while nothing arrives, at most every kNodeCheckPeriod.
    bool node_present();
    static constexpr std::chrono::milliseconds kNodeCheckPeriod{500};

    // Wait between bytes on write, for devices that drop bytes sent back to back.
    void set_inter_byte_spacing(std::chrono::microseconds spacing) { spacing_ = spacing; }

    ReadResult read(uint8_t* buf, std::size_t cap, int timeout_ms) override;
    bool write(const uint8_t* data, std::size_t n) override;
    bool set_baud(int baud) override;
    int baud() const override { return baud_; }
    void flush_input() override;
    void drain_output() override;
    const std::string& last_error() const override { return error_; }

private:
    bool fail(const std::string& what);

    int fd_ = -1;
    int baud_ = 0;
    std::string path_;
    std::string error_;
    std::chrono::microseconds spacing_{0};
    dev_t rdev_ = 0;               // the open device's node: compared with path() while quiet
    ino_t ino_ = 0;
    int64_t next_node_check_us_ = 0;  // monotonic
};

// Sets baud on any tty fd (termios2 with BOTHER, so non-standard rates work). False if refused.
bool set_tty_baud(int fd, int baud);
// The input baud rate of the tty fd, as termios2 reports it (works on a pty master, where it
// returns what the slave side set). -1 on error.
int get_tty_baud(int fd);
// Seconds to transmit n bytes at baud with 8N1 framing (10 bits per byte).
double transmission_time_s(std::size_t n, int baud);

}  // namespace ugv::io
