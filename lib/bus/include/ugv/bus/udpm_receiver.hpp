// The receiving half of LCM udpm, on the caller's thread. liblcm 1.3.1 receives on a thread
// of its own that wakes for every datagram on the group and wakes the caller again through a
// pipe for each message it wants; on a 2-core vehicle computer those wake-ups, not the
// messages, were most of a subscriber's CPU (docs/performance.md). Here one non-blocking
// socket joins the group, recvmmsg() takes up to a batch of datagrams per call, and the
// caller decides how often to drain it, and each drain reads a bounded number of datagrams
// (a flood must not keep the caller from its own work). Publishing stays with liblcm.
#pragma once

#include <cstddef>
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
    uint64_t budget_stops = 0;  // drains that stopped at their budget with more waiting, maybe
};

// What one drain() reads at most: enough for everything a 4 MiB socket buffer holds of
// ordinary traffic, little enough to take a millisecond or two.
struct DrainBudget
{
    std::size_t datagrams = 1024;
    std::size_t bytes = 4u << 20;
};

struct DrainResult
{
    std::size_t handed = 0;  // messages the sink wanted
    bool budget_spent = false;  // stopped at the budget, not because the socket was empty
};

class UdpmReceiver
{
public:
    // Joins url's group on its port. Throws BusError with one line (the URL and why).
    explicit UdpmReceiver(const UdpmUrl& url, ReassemblyLimits limits = {});
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
    // Reads the datagrams already waiting, without blocking, up to the budget, and hands each
    // complete message to `sink`, in arrival order. With `wants`, fragmented messages on
    // channels it does not want are not reassembled (counted in reassembly().unwanted_messages).
    DrainResult drain(const Sink& sink, DrainBudget budget = {}, const LcmReassembler::Wants* wants = nullptr);

    const UdpmReceiverCounters& counters() const { return counters_; }
    const ReassemblyCounters& reassembly() const { return reassembler_.counters(); }
    std::size_t reassembly_bytes_held() const { return reassembler_.bytes_held(); }

private:
    int fd_ = -1;
    int receive_buffer_bytes_ = 0;
    std::vector<uint8_t> buffers_;  // kBatch datagrams of up to 64 KiB
    std::vector<uint8_t> control_;  // their SO_TIMESTAMP control messages
    LcmReassembler reassembler_;
    UdpmReceiverCounters counters_;
};

}  // namespace ugv::bus::detail
