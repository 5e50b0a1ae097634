// The byte transport a device session talks through. SerialPort implements it on a real
// tty; tests can implement it on anything. Sessions in drivers/ see only this interface.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace ugv::io {

struct ReadResult
{
    enum class Status {
        data,     // n > 0 bytes were read
        timeout,  // nothing arrived within the timeout
        closed,   // the device went away (hang-up, EIO, unplugged): reopen it
        error     // another error; see the stream's last_error()
    };
    Status status = Status::timeout;
    std::size_t n = 0;
    int64_t utime = 0;  // CLOCK_REALTIME read right after poll() woke: the chunk's arrival time
};

class ByteStream
{
public:
    virtual ~ByteStream() = default;
    // Waits up to timeout_ms (0 = do not wait) for bytes and reads what is there, up to cap.
    virtual ReadResult read(uint8_t* buf, std::size_t cap, int timeout_ms) = 0;
    // Writes all n bytes (blocking until they are queued). False on error.
    virtual bool write(const uint8_t* data, std::size_t n) = 0;
    // Changes the line speed, any rate (standard or not, e.g. 500000). False if refused.
    virtual bool set_baud(int baud) = 0;
    virtual int baud() const = 0;
    // Discards whatever was received and not read yet.
    virtual void flush_input() = 0;
    // Blocks until everything written has left the host (tcdrain).
    virtual void drain_output() {}
    virtual const std::string& last_error() const = 0;
};

}  // namespace ugv::io
