// What a udpm subscriber reads off the group, as the receiver parses and reassembles it: the
// input is a sequence of datagrams, each [sender byte][u16 length][bytes]. Invariants: a
// datagram is never read outside its bytes (ASan), a short message's channel and payload lie
// inside it; a completed message has a non-empty channel of at most 63 characters without
// NUL and exactly the payload size its fragments announced; reassembly state stays bounded.
#include <cstdlib>
#include <cstring>

#include "ugv/bus/lcm_datagram.hpp"

using namespace ugv::bus::detail;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    LcmReassembler reassembler;
    LcmReassembler::Message done;
    size_t at = 0;
    while (at + 3 <= size) {
        const uint64_t sender = data[at] % 4;  // a few senders, so messages interleave
        const size_t length = static_cast<size_t>(data[at + 1]) << 8 | data[at + 2];
        at += 3;
        const size_t n = length < size - at ? length : size - at;
        // A copy of exactly n bytes: ASan then catches any read past the datagram.
        uint8_t* datagram = static_cast<uint8_t*>(std::malloc(n ? n : 1));
        std::memcpy(datagram, data + at, n);
        at += n;
        const LcmDatagram d = parse_lcm_datagram(datagram, n);
        if (d.kind == LcmDatagram::Kind::short_message) {
            if (d.channel.empty() || d.channel.size() > kLcmMaxChannelLength) std::abort();
            if (d.payload < datagram || d.payload + d.payload_size != datagram + n) std::abort();
        } else if (reassembler.add_fragment(sender, d, done)) {
            if (done.channel.empty() || done.channel.size() > kLcmMaxChannelLength) std::abort();
            if (done.channel.find('\0') != std::string::npos) std::abort();
            if (done.payload.size() != d.message_size) std::abort();
        }
        std::free(datagram);
    }
    return 0;
}
