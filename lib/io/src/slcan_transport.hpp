// slcan over a SerialPort: the CanTransport for Lawicel-protocol USB adapters.
#pragma once

#include <deque>

#include "ugv/io/can_transport.hpp"
#include "ugv/io/serial_port.hpp"
#include "ugv/io/slcan_codec.hpp"

namespace ugv::io {

class SlcanTransport final : public CanTransport
{
public:
    SlcanTransport(std::string device, int serial_baud, int bitrate);
    bool open() override;
    void close() override;
    bool send(const CanFrame& frame) override;
    CanReceive receive(int timeout_ms) override;
    int fd() const override { return port_.fd(); }
    bool stamps_arrival() const override { return false; }
    std::string describe() const override;
    const std::string& last_error() const override { return error_; }

private:
    // Sends a command and waits for the adapter's CR (ok) or BEL (error).
    bool command(const std::string& cmd, int timeout_ms);
    void fill(int timeout_ms);

    std::string device_;
    int serial_baud_;
    int bitrate_;
    SerialPort port_;
    slcan::Decoder decoder_;
    std::deque<CanReceive> pending_;
    std::string error_;
};

}  // namespace ugv::io
