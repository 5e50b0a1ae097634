// The receiving half of LCM udpm, on the caller's thread. liblcm 1.3.1 receives on a thread
// of its own that wakes for every datagram on the group and wakes the caller again through a
// pipe for each message it wants; on a 2-core vehicle computer those wake-ups, not the
// messages, were most of a subscriber's CPU (docs/performance.md). Here one non-blocking
// socket joins the group, recvmmsg() takes up to a batch of datagrams per call, and the
// caller decides how often to drain it. Publishing stays with liblcm.
#pragma once

#include <cstdint>
#include <functional>
#include <string_view>
#include <vector>

#include "ugv/bus/lcm_datagram.hpp"
#include "ugv/bus/udpm_url.hpp"

namespace ugv::bus::detail {

struct UdpmReceiverCounters
{
    uint64_t datagrams = 0;
    uint64_t messages = 0;  // complete messages handed out (wanted or not)
};

class UdpmReceiver
{
public:
    // Joins url's group on its port. Throws BusError with one line (the URL and why).
    explicit UdpmReceiver(const UdpmUrl& url);
    ~UdpmReceiver();
    UdpmReceiver(const UdpmReceiver&) = delete;
    UdpmReceiver& operator=(const UdpmReceiver&) = delete;

    int fd() const { return fd_; }
    // What the kernel granted of SO_RCVBUF (the request, unless net.core.rmem_max is lower).
    int receive_buffer_bytes() const { return receive_buffer_bytes_; }
    static constexpr int kDefaultReceiveBufferBytes = 2 << 20;

    // channel, payload, size, the kernel's receive time of the (last) datagram, us since the
    // epoch; returns whether the message was wanted (someone subscribed to its channel).
    using Sink = std::function<bool(std::string_view channel, const uint8_t* data, std::size_t size, int64_t recv_utime)>;
    // Reads every datagram already waiting, without blocking, and hands each complete message
    // to `sink`, in arrival order. Returns how many the sink wanted.
    std::size_t drain(const Sink& sink);

    const UdpmReceiverCounters& counters() const { return counters_; }
    const ReassemblyCounters& reassembly() const { return reassembler_.counters(); }

private:
    int fd_ = -1;
    int receive_buffer_bytes_ = 0;
    std::vector<uint8_t> buffers_;  // kBatch datagrams of up to 64 KiB
    std::vector<uint8_t> control_;  // their SO_TIMESTAMP control messages
    LcmReassembler reassembler_;
    UdpmReceiverCounters counters_;
};

}  // namespace ugv::bus::detail
