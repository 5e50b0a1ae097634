// An emulated Lawicel/slcan USB-CAN adapter, without I/O: ASCII bytes from the host in,
// frames onto the bus and ASCII replies out. S0-S8 (bitrate, only while closed), O (open),
// L (listen only), C (close), F (status), V/N (version, serial), Z0/Z1 (time stamps),
// t/T/r/R (transmit, acknowledged with z/Z). Errors answer BEL, as the real ones do; so
// does every transmit while the controller is bus-off.
//
// Faults: the bus may run at another bitrate than the host sets (nothing passes either way,
// as between controllers that cannot decode each other's bits: transmits are still queued
// and acknowledged), and every n-th transmit may be refused with BEL.
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
    // The bitrate code (n of S<n>) the bus really runs at; -1 = whatever the host sets.
    void set_bus_bitrate_code(int code) { bus_bitrate_code_ = code; }
    // Every n-th transmit is answered BEL and not sent (0 = never).
    void set_refuse_tx_every(unsigned n) { refuse_tx_every_ = n; }

    bool is_open() const { return open_; }
    bool is_bus_off() const { return bus_off_; }
    int bitrate_code() const { return bitrate_code_; }  // the n of S<n>, -1 = never set
    uint64_t errors() const { return errors_; }
    uint64_t tx_refused() const { return tx_refused_; }

private:
    void command(const std::string& line, int64_t now_us, std::vector<io::CanFrame>& frames);
    void bell();
    std::string stamp(int64_t now_us) const;
    bool bitrate_matches() const { return bus_bitrate_code_ < 0 || bus_bitrate_code_ == bitrate_code_; }

    std::string line_;
    std::string output_;
    bool open_ = false;
    bool listen_only_ = false;
    bool bus_off_ = false;
    bool timestamps_ = false;
    int bitrate_code_ = -1;
    uint64_t errors_ = 0;
    int bus_bitrate_code_ = -1;
    unsigned refuse_tx_every_ = 0;
    uint64_t transmits_ = 0;
    uint64_t tx_refused_ = 0;
};

}  // namespace ugv::sim::servo
