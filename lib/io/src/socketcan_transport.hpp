// SocketCAN: a raw CAN socket on a kernel interface (can0), with error frames and kernel
// receive time stamps. The production transport on the vehicle.
#pragma once

#include "ugv/io/can_transport.hpp"

namespace ugv::io {

class SocketCanTransport final : public CanTransport
{
public:
    explicit SocketCanTransport(std::string interface);
    ~SocketCanTransport() override;
    bool open() override;
    void close() override;
    bool send(const CanFrame& frame) override;
    CanReceive receive(int timeout_ms) override;
    int fd() const override { return fd_; }
    bool stamps_arrival() const override { return true; }
    std::string describe() const override { return "socketcan:" + interface_; }
    const std::string& last_error() const override { return error_; }

private:
    std::string interface_;
    int fd_ = -1;
    std::string error_;
};

}  // namespace ugv::io
