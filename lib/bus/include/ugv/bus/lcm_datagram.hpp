// LCM's UDP multicast wire format (the datagrams liblcm 1.3.1 sends), decoded from bytes,
// and the reassembly of fragmented messages. No sockets here: the receiver feeds datagrams in.
//
// Two datagram kinds, every integer big-endian:
//   short  "LC02": u32 magic 0x4c433032, u32 sequence, channel NUL-terminated, payload
//   fragment "LC03": u32 magic 0x4c433033, u32 sequence, u32 payload size, u32 offset of this
//          fragment in the payload, u16 fragment number, u16 fragment count; fragment 0 then
//          carries the channel NUL-terminated; every fragment then carries its payload bytes.
// liblcm fragments a message whose channel + payload exceed 65499 bytes; losing any fragment
// loses the message, which is why the reassembler counts what it abandons.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace ugv::bus::detail {

constexpr uint32_t kLcmShortMagic = 0x4c433032;     // "LC02"
constexpr uint32_t kLcmFragmentMagic = 0x4c433033;  // "LC03"
constexpr std::size_t kLcmMaxChannelLength = 63;    // liblcm's limit, without the NUL
// The largest message the reassembler accepts (a 225 kB map is far below; a datagram that
// claims gigabytes is garbage, not a reason to allocate them).
constexpr uint32_t kLcmMaxMessageBytes = 64u << 20;
// A fragment carries at most one UDP payload: a message cannot be larger than its fragment
// count times this (so a lone 20-byte datagram cannot claim 64 MiB with one fragment).
constexpr uint32_t kLcmMaxFragmentBytes = 65535;

struct LcmDatagram
{
    enum class Kind { short_message, fragment, invalid };
    Kind kind = Kind::invalid;
    uint32_t sequence = 0;
    std::string_view channel;    // short messages and fragment 0 only
    const uint8_t* payload = nullptr;
    std::size_t payload_size = 0;
    // Fragments only:
    uint32_t message_size = 0;   // the whole payload
    uint32_t offset = 0;         // of this fragment's bytes in the payload
    uint16_t fragment_no = 0;
    uint16_t fragment_count = 0;
};

// Decodes one datagram; Kind::invalid for anything that is not a well-formed LCM datagram
// (wrong magic, no NUL within the channel limit, a fragment outside its message).
LcmDatagram parse_lcm_datagram(const uint8_t* data, std::size_t size);

// What reassembly counts.
struct ReassemblyCounters
{
    uint64_t invalid_datagrams = 0;     // not LCM, or inconsistent with their message
    uint64_t incomplete_messages = 0;   // fragmented messages abandoned with fragments missing
};

// Puts fragmented messages back together, one message in progress per sender (as liblcm
// does: a sender's fragments arrive in order on one host or one link, and a new sequence
// number from that sender means the old message lost a fragment). Fragments may arrive in
// any order within their message; duplicates are ignored.
class LcmReassembler
{
public:
    struct Message
    {
        std::string channel;
        std::vector<uint8_t> payload;
    };

    // sender: any key unique per sending socket (address and port). Returns true and fills
    // `done` when this fragment completes its message.
    bool add_fragment(uint64_t sender, const LcmDatagram& fragment, Message& done);

    const ReassemblyCounters& counters() const { return counters_; }
    ReassemblyCounters& counters() { return counters_; }
    // The payload bytes held for unfinished messages (at most kMaxBytesInProgress).
    std::size_t bytes_in_progress() const { return bytes_in_progress_; }

private:
    struct InProgress
    {
        uint64_t sender = 0;
        uint32_t sequence = 0;
        uint16_t fragment_count = 0;
        uint16_t received = 0;
        std::size_t bytes = 0;  // payload bytes received: must add up to the message size
        uint64_t last_use = 0;
        std::vector<bool> have;
        Message message;
    };
    InProgress& slot_for(uint64_t sender);

    static constexpr std::size_t kMaxSenders = 32;  // beyond: the least recently used is dropped
    // The payload buffers of all unfinished messages together; a message that would exceed it
    // drops the least recently used unfinished ones (garbage claiming big sizes cannot make
    // the receiver allocate without bound).
    static constexpr std::size_t kMaxBytesInProgress = 96u << 20;
    void make_room(std::size_t bytes, const InProgress* keep);
    std::size_t bytes_in_progress_ = 0;
    std::vector<InProgress> in_progress_;
    uint64_t clock_ = 0;
    ReassemblyCounters counters_;
};

}  // namespace ugv::bus::detail
