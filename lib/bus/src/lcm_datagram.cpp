#include "ugv/bus/lcm_datagram.hpp"

#include <algorithm>
#include <cstring>

namespace ugv::bus::detail {
namespace {

// Per sender, buffers up to this size are kept between messages.
constexpr std::size_t kKeepBytes = 16u << 10;

uint32_t be32(const uint8_t* p)
{
    return (uint32_t{p[0]} << 24) | (uint32_t{p[1]} << 16) | (uint32_t{p[2]} << 8) | uint32_t{p[3]};
}
uint16_t be16(const uint8_t* p) { return static_cast<uint16_t>((p[0] << 8) | p[1]); }

// The channel at p (at most `size` bytes, NUL-terminated within liblcm's limit); its length
// with the NUL, or 0 when there is none.
std::size_t channel_span(const uint8_t* p, std::size_t size)
{
    const std::size_t limit = std::min(size, kLcmMaxChannelLength + 1);
    const void* nul = std::memchr(p, 0, limit);
    if (!nul) return 0;
    const std::size_t length = static_cast<std::size_t>(static_cast<const uint8_t*>(nul) - p);
    return length == 0 ? 0 : length + 1;
}

}  // namespace

LcmDatagram parse_lcm_datagram(const uint8_t* data, std::size_t size)
{
    LcmDatagram d;
    d.size = size;
    if (size < 8) return d;
    const uint32_t magic = be32(data);
    d.sequence = be32(data + 4);
    if (magic == kLcmShortMagic) {
        const std::size_t ch = channel_span(data + 8, size - 8);
        if (ch == 0) return d;
        d.channel = std::string_view(reinterpret_cast<const char*>(data + 8), ch - 1);
        d.payload = data + 8 + ch;
        d.payload_size = size - 8 - ch;
        d.kind = LcmDatagram::Kind::short_message;
        return d;
    }
    if (magic != kLcmFragmentMagic || size < 20) return d;
    d.message_size = be32(data + 8);
    d.offset = be32(data + 12);
    d.fragment_no = be16(data + 16);
    d.fragment_count = be16(data + 18);
    std::size_t header = 20;
    if (d.fragment_no == 0) {
        const std::size_t ch = channel_span(data + 20, size - 20);
        if (ch == 0) return d;
        d.channel = std::string_view(reinterpret_cast<const char*>(data + 20), ch - 1);
        header += ch;
    }
    d.payload = data + header;
    d.payload_size = size - header;
    const bool consistent = d.fragment_count >= 1 && d.fragment_no < d.fragment_count &&
                            d.message_size <= kLcmMaxMessageBytes &&
                            d.message_size <= uint64_t{d.fragment_count} * kLcmMaxFragmentBytes &&
                            d.offset <= d.message_size &&
                            d.payload_size <= d.message_size - d.offset && (d.fragment_no != 0 || d.offset == 0);
    if (consistent) d.kind = LcmDatagram::Kind::fragment;
    return d;
}

LcmReassembler::LcmReassembler(ReassemblyLimits limits) : limits_(limits)
{
    in_progress_.reserve(limits_.max_senders);
}

LcmReassembler::InProgress& LcmReassembler::slot_for(uint64_t sender)
{
    InProgress* idle = nullptr;
    InProgress* lru = nullptr;
    for (auto& s : in_progress_) {
        if (s.sender == sender) return s;
        if (!s.active && !idle) idle = &s;
        if (!lru || s.last_use < lru->last_use) lru = &s;
    }
    if (in_progress_.size() < limits_.max_senders) {
        in_progress_.emplace_back();
        in_progress_.back().sender = sender;
        return in_progress_.back();
    }
    // A sender with nothing in progress gives up its slot first; else the least recently used.
    InProgress& s = idle ? *idle : *lru;
    if (s.active) release(s, &counters_.evicted_messages);
    s.sender = sender;
    return s;
}

void LcmReassembler::release(InProgress& s, uint64_t* counter)
{
    if (counter) ++*counter;
    bytes_held_ -= s.charged;
    s.active = false;
    s.unwanted = false;
    s.charged = 0;
    s.payload_bytes = 0;
    // Small buffers are kept for the sender's next message: garbage that begins a message per
    // datagram then allocates nothing, instead of interleaving small blocks with the large
    // ones of real messages (heap fragmentation, a few MB). Large ones are freed.
    s.have.clear();
    s.pieces.clear();
    s.bytes.clear();
    s.channel.clear();
    // (swap: assigning {} to a vector keeps its capacity)
    if (s.bytes.capacity() > kKeepBytes) std::vector<uint8_t>().swap(s.bytes);
    if (s.pieces.capacity() > kKeepBytes / sizeof(Piece)) std::vector<Piece>().swap(s.pieces);
    if (s.have.capacity() > kKeepBytes * 8) std::vector<bool>().swap(s.have);
}

bool LcmReassembler::make_room(std::size_t more, const InProgress* keep)
{
    const std::size_t limit = limits_.bytes_held_limit();
    while (bytes_held_ + more > limit) {
        InProgress* lru = nullptr;
        for (auto& s : in_progress_)
            if (&s != keep && s.active && (!lru || s.last_use < lru->last_use)) lru = &s;
        if (!lru) return false;
        release(*lru, &counters_.evicted_messages);
    }
    return true;
}

void LcmReassembler::expire(int64_t now_utime)
{
    for (auto& s : in_progress_) {
        if (!s.active) continue;
        // Either way: a clock stepped back must not keep a message forever.
        const int64_t age = now_utime - s.started_utime;
        if (age > limits_.max_age_us || age < -limits_.max_age_us) release(s, &counters_.expired_messages);
    }
}

bool LcmReassembler::add_fragment(uint64_t sender, const LcmDatagram& f, int64_t now_utime, Message& done,
                                  const Wants* wants)
{
    bytes_received_ += f.size;
    expire(now_utime);
    if (f.kind != LcmDatagram::Kind::fragment) {
        ++counters_.invalid_datagrams;
        return false;
    }
    if (f.message_size > limits_.max_message_bytes) {
        ++counters_.oversized_messages;  // refused before anything is held
        return false;
    }
    InProgress& s = slot_for(sender);
    s.last_use = ++clock_;
    const bool same_message = s.active && s.sequence == f.sequence;
    if (same_message && (s.fragment_count != f.fragment_count || s.message_size != f.message_size)) {
        ++counters_.invalid_datagrams;  // contradicts the fragments before it
        return false;
    }
    if (!same_message) {
        if (s.active) release(s, &counters_.incomplete_messages);
        s.active = true;
        s.sequence = f.sequence;
        s.message_size = f.message_size;
        s.fragment_count = f.fragment_count;
        s.received = 0;
        s.started_utime = now_utime;
        s.have.assign(f.fragment_count, false);
    }
    if (s.have[f.fragment_no]) return false;  // a duplicate
    if (s.payload_bytes + f.payload_size > s.message_size) {
        ++counters_.invalid_datagrams;  // more bytes than the message has
        return false;
    }
    // Every daemon on the group receives every map (its own looped back too): one nobody
    // here wants is followed to its end, its bytes neither kept nor copied.
    if (f.fragment_no == 0 && wants != nullptr && !(*wants)(f.channel)) {
        bytes_held_ -= s.charged;
        s.charged = 0;
        s.pieces.clear();
        s.bytes.clear();
        s.unwanted = true;
    }
    s.have[f.fragment_no] = true;  // a release below forgets it with the rest
    ++s.received;
    s.payload_bytes += f.payload_size;
    if (s.unwanted) {
        if (s.received < s.fragment_count) return false;
        release(s, s.payload_bytes == s.message_size ? &counters_.unwanted_messages : &counters_.invalid_datagrams);
        return false;
    }
    const std::size_t cost = f.payload_size + kLcmFragmentHeaderBytes;
    if (s.charged + cost > limits_.sender_limit()) {
        release(s, &counters_.oversized_messages);  // a message in countless tiny fragments
        return false;
    }
    if (!make_room(cost, &s)) {
        release(s, &counters_.evicted_messages);
        return false;
    }
    s.charged += cost;
    bytes_held_ += cost;
    if (f.fragment_no == 0) s.channel.assign(f.channel);
    s.pieces.push_back({f.offset, static_cast<uint32_t>(f.payload_size)});
    s.bytes.insert(s.bytes.end(), f.payload, f.payload + f.payload_size);
    if (s.received < s.fragment_count) return false;
    const bool whole = s.payload_bytes == s.message_size && !s.channel.empty();
    if (whole) {
        done.channel = std::move(s.channel);
        done.payload.assign(s.message_size, 0);
        std::size_t at = 0;
        for (const Piece& p : s.pieces) {
            if (p.size > 0) std::memcpy(done.payload.data() + p.offset, s.bytes.data() + at, p.size);
            at += p.size;
        }
    } else {
        ++counters_.invalid_datagrams;  // fragments that do not tile their message
    }
    release(s, nullptr);
    return whole;
}

}  // namespace ugv::bus::detail
