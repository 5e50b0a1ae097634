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
#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace ugv::bus::detail {

constexpr uint32_t kLcmShortMagic = 0x4c433032;     // "LC02"
constexpr uint32_t kLcmFragmentMagic = 0x4c433033;  // "LC03"
constexpr std::size_t kLcmMaxChannelLength = 63;    // liblcm's limit, without the NUL
// The largest message size a fragment header may claim at all; the reassembler's own limit
// (ReassemblyLimits::max_message_bytes, the daemons' `bus_max_message_bytes`) is lower.
constexpr uint32_t kLcmMaxMessageBytes = 64u << 20;
// A fragment carries at most one UDP payload: a message cannot be larger than its fragment
// count times this.
constexpr uint32_t kLcmMaxFragmentBytes = 65535;
// The header every fragment datagram carries: what reassembly charges per fragment held for
// its bookkeeping, so a flood of empty fragments costs budget too.
constexpr std::size_t kLcmFragmentHeaderBytes = 20;

struct LcmDatagram
{
    enum class Kind { short_message, fragment, invalid };
    Kind kind = Kind::invalid;
    uint32_t sequence = 0;
    std::size_t size = 0;        // the whole datagram
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

// What reassembly counts. Every unfinished message it lets go is counted in exactly one of
// incomplete, oversized, expired or evicted.
struct ReassemblyCounters
{
    uint64_t invalid_datagrams = 0;     // not LCM, or inconsistent with their message
    uint64_t incomplete_messages = 0;   // abandoned for a newer message of the same sender (a lost fragment)
    uint64_t oversized_messages = 0;    // claimed more than max_message_bytes, or outgrew a sender's share
    uint64_t expired_messages = 0;      // unfinished after max_age_us
    uint64_t evicted_messages = 0;      // the least recently used, dropped to stay within the bounds
    uint64_t unwanted_messages = 0;     // complete, on a channel nobody here subscribed to: not kept
};

// The bounds of reassembly. Memory is charged as it arrives: each fragment held costs its
// payload plus kLcmFragmentHeaderBytes, never the size its header claims.
struct ReassemblyLimits
{
    std::size_t max_message_bytes = 1u << 20;  // a larger claimed size is refused at once
    // Charged bytes of all unfinished messages together: 0 = 4 x max_message_bytes (room for
    // a few large messages in progress at once, from different senders).
    std::size_t max_bytes_held = 0;
    // A message whose first fragment came longer ago is dropped (liblcm sends all fragments
    // of a message in one burst, within milliseconds).
    int64_t max_age_us = 1'000'000;
    std::size_t max_senders = 32;  // messages in progress at once, one per sender

    std::size_t bytes_held_limit() const { return max_bytes_held ? max_bytes_held : 4 * max_message_bytes; }
    // One sender's message: its payload and the header charge of its fragments (liblcm's
    // smallest fragments, 1400 bytes in old versions, cost 1.5 %).
    std::size_t sender_limit() const { return max_message_bytes + max_message_bytes / 8; }
};

// Puts fragmented messages back together, one message in progress per sender (as liblcm
// does: a sender's fragments arrive in order on one host or one link, and a new sequence
// number from that sender means the old message lost a fragment). Fragments may arrive in
// any order within their message; duplicates are ignored. Fragments are kept as they come
// (in arrival order) and laid out only when the last one arrives, so what is held never
// exceeds what was received.
class LcmReassembler
{
public:
    struct Message
    {
        std::string channel;
        std::vector<uint8_t> payload;
    };

    explicit LcmReassembler(ReassemblyLimits limits = {});

    // Whether a channel is subscribed to here.
    using Wants = std::function<bool(std::string_view channel)>;

    // sender: any key unique per sending socket (address and port); now_utime: when the
    // datagram arrived (us, any clock that the caller keeps using). Returns true and fills
    // `done` when this fragment completes its message. With `wants`, a message whose channel
    // (in its fragment 0) is not wanted is followed to its end without keeping its bytes.
    bool add_fragment(uint64_t sender, const LcmDatagram& fragment, int64_t now_utime, Message& done,
                      const Wants* wants = nullptr);
    // Drops unfinished messages older than max_age_us (add_fragment does it too).
    void expire(int64_t now_utime);

    const ReassemblyLimits& limits() const { return limits_; }
    const ReassemblyCounters& counters() const { return counters_; }
    ReassemblyCounters& counters() { return counters_; }
    // The bytes charged for unfinished messages now (at most limits().bytes_held_limit()).
    std::size_t bytes_held() const { return bytes_held_; }
    // Datagram bytes given to add_fragment so far; bytes_held() never exceeds it.
    uint64_t bytes_received() const { return bytes_received_; }

private:
    struct Piece
    {
        uint32_t offset;  // in the message
        uint32_t size;
    };
    struct InProgress
    {
        uint64_t sender = 0;
        bool active = false;
        uint32_t sequence = 0;
        uint32_t message_size = 0;
        uint16_t fragment_count = 0;
        uint16_t received = 0;
        std::size_t payload_bytes = 0;
        std::size_t charged = 0;  // payload_bytes + kLcmFragmentHeaderBytes per piece
        bool unwanted = false;    // its channel is nobody's here: its bytes are not kept
        int64_t started_utime = 0;
        uint64_t last_use = 0;
        std::vector<bool> have;       // by fragment number
        std::vector<Piece> pieces;    // in arrival order
        std::vector<uint8_t> bytes;   // their payloads, in arrival order
        std::string channel;
    };
    InProgress& slot_for(uint64_t sender);
    // Lets go of s's message, counted in `counter` (nullptr: completed).
    void release(InProgress& s, uint64_t* counter);
    // Evicts least recently used messages (not `keep`) until `more` bytes fit.
    bool make_room(std::size_t more, const InProgress* keep);

    ReassemblyLimits limits_;
    std::size_t bytes_held_ = 0;
    uint64_t bytes_received_ = 0;
    std::vector<InProgress> in_progress_;
    uint64_t clock_ = 0;
    ReassemblyCounters counters_;
};

}  // namespace ugv::bus::detail
