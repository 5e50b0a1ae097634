#include "ugv/bus/lcm_datagram.hpp"

#include <algorithm>
#include <cstring>

namespace ugv::bus::detail {
namespace {

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

LcmReassembler::InProgress& LcmReassembler::slot_for(uint64_t sender)
{
    for (auto& s : in_progress_)
        if (s.sender == sender) return s;
    if (in_progress_.size() < kMaxSenders) {
        in_progress_.emplace_back();
        in_progress_.back().sender = sender;
        return in_progress_.back();
    }
    auto& oldest = *std::min_element(in_progress_.begin(), in_progress_.end(),
                                     [](const InProgress& a, const InProgress& b) { return a.last_use < b.last_use; });
    if (oldest.fragment_count != 0) ++counters_.incomplete_messages;
    bytes_in_progress_ -= oldest.message.payload.size();
    oldest = InProgress{};
    oldest.sender = sender;
    return oldest;
}

void LcmReassembler::make_room(std::size_t bytes, const InProgress* keep)
{
    while (bytes_in_progress_ + bytes > kMaxBytesInProgress) {
        InProgress* lru = nullptr;
        for (auto& s : in_progress_)
            if (&s != keep && s.fragment_count != 0 && (!lru || s.last_use < lru->last_use)) lru = &s;
        if (!lru) return;
        ++counters_.incomplete_messages;
        bytes_in_progress_ -= lru->message.payload.size();
        const uint64_t sender = lru->sender;
        *lru = InProgress{};
        lru->sender = sender;
    }
}

bool LcmReassembler::add_fragment(uint64_t sender, const LcmDatagram& f, Message& done)
{
    if (f.kind != LcmDatagram::Kind::fragment) {
        ++counters_.invalid_datagrams;
        return false;
    }
    InProgress& s = slot_for(sender);
    s.last_use = ++clock_;
    const bool same_message = s.fragment_count != 0 && s.sequence == f.sequence;
    if (same_message && (s.fragment_count != f.fragment_count || s.message.payload.size() != f.message_size)) {
        ++counters_.invalid_datagrams;  // contradicts the fragments before it
        return false;
    }
    if (!same_message) {
        if (s.fragment_count != 0) ++counters_.incomplete_messages;
        bytes_in_progress_ -= s.message.payload.size();
        s.message.payload = {};
        make_room(f.message_size, &s);
        bytes_in_progress_ += f.message_size;
        s.sequence = f.sequence;
        s.fragment_count = f.fragment_count;
        s.received = 0;
        s.bytes = 0;
        s.have.assign(f.fragment_count, false);
        s.message.channel.clear();
        s.message.payload.assign(f.message_size, 0);
    }
    if (s.have[f.fragment_no]) return false;  // a duplicate
    s.have[f.fragment_no] = true;
    ++s.received;
    s.bytes += f.payload_size;
    if (f.fragment_no == 0) s.message.channel.assign(f.channel);
    if (f.payload_size > 0) std::memcpy(s.message.payload.data() + f.offset, f.payload, f.payload_size);
    if (s.received < s.fragment_count) return false;
    const bool whole = s.bytes == s.message.payload.size() && !s.message.channel.empty();
    bytes_in_progress_ -= s.message.payload.size();
    if (whole) done = std::move(s.message);
    else ++counters_.invalid_datagrams;  // fragments that do not tile their message
    s.message = Message{};
    s.fragment_count = 0;  // nothing in progress
    s.have.clear();
    return whole;
}

}  // namespace ugv::bus::detail
