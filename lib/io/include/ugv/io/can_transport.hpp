// The CAN frame transport: SocketCAN (production, a raw socket on can0) or slcan (a Lawicel
// ASCII adapter on a serial port, the one the build machines can run). The CANopen layer
// sees only this interface.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "ugv/io/can_frame.hpp"

namespace ugv::io {

struct CanReceive
{
    enum class Status { frame, timeout, bus_error, closed, error };
    Status status = Status::timeout;
    CanFrame frame;      // valid when status == frame
    int64_t utime = 0;   // receive time, us since the Unix epoch
    std::string detail;  // for bus_error/error: what the transport said
};

class CanTransport
{
public:
    virtual ~CanTransport() = default;
    // Opens the bus (brings up the adapter at the configured bitrate). False on failure,
    // with last_error() saying why in one line.
    virtual bool open() = 0;
    virtual void close() = 0;
    virtual bool send(const CanFrame& frame) = 0;
    virtual CanReceive receive(int timeout_ms) = 0;
    // For poll(): readable when a frame may be waiting. -1 when closed.
    virtual int fd() const = 0;
    // True when CanReceive::utime is when the frame arrived however late it is read (the
    // kernel's SO_TIMESTAMP); false when it is the time of the read that found it (slcan:
    // bytes on a serial port carry no time).
    virtual bool stamps_arrival() const = 0;
    virtual std::string describe() const = 0;
    virtual const std::string& last_error() const = 0;
};

// "socketcan:can0" or "slcan:/dev/ttyACM0@115200" (serial baud after @, default 115200).
// bitrate is the CAN bus bitrate in bit/s. Throws std::invalid_argument with a one-line
// reason for a malformed spec (a configuration error, found at start-up).
std::unique_ptr<CanTransport> make_can_transport(const std::string& spec, int bitrate);

// True when this kernel lets us open an AF_CAN socket (SocketCAN is there).
bool socketcan_available();

}  // namespace ugv::io
