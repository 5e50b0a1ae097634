// What a udpm subscriber reads off the group, as the receiver parses and reassembles it: the
// input is a sequence of datagrams, each [sender byte][time step byte, x 10 us][u16 length]
// [bytes], into a reassembler with small bounds (so inputs of a few kB reach them all).
// Invariants: a datagram is never read outside its bytes (ASan); a short message's channel
// and payload lie inside it; a completed message has a non-empty channel of at most 63
// characters without NUL, exactly the payload size its fragments announced, and no more
// than max_message_bytes; the bytes held never exceed the budget nor the bytes received;
// once every message is past its age, nothing is held.
#include <cstdlib>
#include <cstring>

#include "ugv/bus/lcm_datagram.hpp"

using namespace ugv::bus::detail;

namespace {

ReassemblyLimits small_limits()
{
    ReassemblyLimits l;
    l.max_message_bytes = 1000;
    l.max_bytes_held = 1400;  // two 600-byte messages at once, not three
    l.max_age_us = 1000;
    l.max_senders = 4;
    return l;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    const ReassemblyLimits limits = small_limits();
    LcmReassembler reassembler(limits);
    LcmReassembler::Message done;
    int64_t now = 1'700'000'000'000'000;
    size_t at = 0;
    while (at + 4 <= size) {
        const uint64_t sender = data[at] % 8;  // more senders than slots, so messages interleave and evict
        now += int64_t{data[at + 1]} * 10;
        const size_t length = static_cast<size_t>(data[at + 2]) << 8 | data[at + 3];
        at += 4;
        const size_t n = length < size - at ? length : size - at;
        // A copy of exactly n bytes: ASan then catches any read past the datagram.
        uint8_t* datagram = static_cast<uint8_t*>(std::malloc(n ? n : 1));
        std::memcpy(datagram, data + at, n);
        at += n;
        const LcmDatagram d = parse_lcm_datagram(datagram, n);
        if (d.kind == LcmDatagram::Kind::short_message) {
            if (d.channel.empty() || d.channel.size() > kLcmMaxChannelLength) std::abort();
            if (d.payload < datagram || d.payload + d.payload_size != datagram + n) std::abort();
        } else if (reassembler.add_fragment(sender, d, now, done)) {
            if (done.channel.empty() || done.channel.size() > kLcmMaxChannelLength) std::abort();
            if (done.channel.find('\0') != std::string::npos) std::abort();
            if (done.payload.size() != d.message_size) std::abort();
            if (done.payload.size() > limits.max_message_bytes) std::abort();
        }
        if (reassembler.bytes_held() > limits.bytes_held_limit()) std::abort();
        if (reassembler.bytes_held() > reassembler.bytes_received()) std::abort();
        std::free(datagram);
    }
    reassembler.expire(now + limits.max_age_us + 1);
    if (reassembler.bytes_held() != 0) std::abort();
    return 0;
}
