// An emulated Lawicel/slcan USB-CAN adapter, without I/O: ASCII bytes from the host in,
// frames onto the bus and ASCII replies out. S0-S8 (bitrate, only while closed), O (open),
// L (listen only), C (close), F (status), V/N (version, serial), Z0/Z1 (time stamps),
// t/T/r/R (transmit, acknowledged with z/Z). Errors answer BEL, as the real ones do; so
// does every transmit while the controller is bus-off.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "ugv/io/can_frame.hpp"

namespace ugv::sim::servo {

class SlcanAdapter
{
public:
    // Host bytes: returns the frames the host transmitted onto the bus. Replies accumulate
    // in take_output().
    std::vector<io::CanFrame> feed(const uint8_t* data, std::size_t n, int64_t now_us);
    // A frame on the bus goes to the host when the channel is open.
    void on_bus_frame(const io::CanFrame& frame, int64_t now_us);
    std::string take_output() { return std::exchange(output_, {}); }

    // The CAN controller went bus-off: one BEL now, and nothing passes either way until the
    // host closes the channel (C) and opens it again (the explicit restart bus-off needs).
    void bus_off();

    bool is_open() const { return open_; }
    bool is_bus_off() const { return bus_off_; }
    int bitrate_code() const { return bitrate_code_; }  // the n of S<n>, -1 = never set
    uint64_t errors() const { return errors_; }

private:
    void command(const std::string& line, int64_t now_us, std::vector<io::CanFrame>& frames);
    void bell();
    std::string stamp(int64_t now_us) const;

    std::string line_;
    std::string output_;
    bool open_ = false;
    bool listen_only_ = false;
    bool bus_off_ = false;
    bool timestamps_ = false;
    int bitrate_code_ = -1;
    uint64_t errors_ = 0;
};

}  // namespace ugv::sim::servo
