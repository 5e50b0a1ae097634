#include "ugv/novatel/stream_splitter.hpp"

#include <cstring>

#include "ugv/novatel/checksum.hpp"

namespace ugv::novatel {
namespace {

constexpr uint8_t kSync0 = 0xAA, kSync1 = 0x44, kSyncLong = 0x12, kSyncShort = 0x13;
constexpr std::size_t kShortHeader = 12;
constexpr std::size_t kCrcBytes = 4;

inline uint16_t le16(const uint8_t* p) { return static_cast<uint16_t>(p[0] | p[1] << 8); }
inline uint32_t le32(const uint8_t* p)
{
    return static_cast<uint32_t>(p[0]) | static_cast<uint32_t>(p[1]) << 8 | static_cast<uint32_t>(p[2]) << 16 |
           static_cast<uint32_t>(p[3]) << 24;
}
// Characters a NovAtel ASCII log or an NMEA sentence may hold before its '*'.
inline bool is_text(uint8_t c) { return (c >= 32 && c <= 126) || c == '\t'; }
inline bool is_line_end(uint8_t c) { return c == '\r' || c == '\n'; }

}  // namespace

const char* frame_kind_name(FrameKind kind)
{
    switch (kind) {
    case FrameKind::binary: return "binary";
    case FrameKind::binary_short: return "binary_short";
    case FrameKind::ascii: return "ascii";
    case FrameKind::ascii_short: return "ascii_short";
    case FrameKind::nmea: return "nmea";
    case FrameKind::reply: return "reply";
    case FrameKind::prompt: return "prompt";
    }
    return "?";
}

uint64_t SplitterCounters::frames_total() const
{
    uint64_t t = 0;
    for (auto f : frames) {
        t += f;
    }
    return t;
}

void StreamSplitter::reset()
{
    buf_.clear();
    text_checked_ = 0;
    in_garbage_ = false;
}

void StreamSplitter::feed(const uint8_t* data, std::size_t n, const Sink& sink)
{
    if (n == 0) {
        return;
    }
    if (buf_.empty()) {
        // Fast path: scan the caller's bytes in place and keep only a partial frame.
        const uint64_t base = fed_;
        fed_ += n;
        const std::size_t used = scan(data, n, base, sink);
        buf_.assign(data + used, data + n);
        return;
    }
    const uint64_t base = fed_ - buf_.size();
    fed_ += n;
    buf_.insert(buf_.end(), data, data + n);
    const std::size_t used = scan(buf_.data(), buf_.size(), base, sink);
    buf_.erase(buf_.begin(), buf_.begin() + static_cast<std::ptrdiff_t>(used));
}

void StreamSplitter::skip_byte()
{
    ++counters_.skipped_bytes;
    if (!in_garbage_) {
        in_garbage_ = true;
        ++counters_.resyncs;
    }
}

std::size_t StreamSplitter::scan(const uint8_t* data, std::size_t n, uint64_t base, const Sink& sink)
{
    std::size_t pos = 0;
    while (pos < n) {
        const uint8_t* p = data + pos;
        const std::size_t avail = n - pos;
        Candidate c{Step::skip, FrameKind::binary, 0, 1};
        switch (*p) {
        case kSync0: c = try_binary(p, avail); break;
        case '#': c = try_text(p, avail, FrameKind::ascii, limits_.max_ascii_line, 8); break;
        case '%': c = try_text(p, avail, FrameKind::ascii_short, limits_.max_ascii_line, 8); break;
        case '$': c = try_text(p, avail, FrameKind::nmea, limits_.max_nmea_line, 2); break;
        case '<': c = try_reply(p, avail); break;
        case '[': c = try_prompt(p, avail); break;
        case '\r':
        case '\n':
            ++pos;  // line ends between frames are not garbage
            continue;
        default: break;
        }
        if (c.step == Step::need_more) {
            return pos;
        }
        text_checked_ = 0;
        if (c.step == Step::skip) {
            skip_byte();
            ++pos;
            continue;
        }
        in_garbage_ = false;
        ++counters_.frames[static_cast<std::size_t>(c.kind)];
        sink(FrameView{c.kind, p, c.size, base + pos + c.size});
        pos += c.consumed;
    }
    return pos;
}

StreamSplitter::Candidate StreamSplitter::try_binary(const uint8_t* p, std::size_t avail)
{
    const Candidate skip{Step::skip, FrameKind::binary, 0, 1};
    const Candidate more{Step::need_more, FrameKind::binary, 0, 0};
    if (avail < 3) {
        return (avail < 2 || p[1] == kSync1) ? more : skip;
    }
    if (p[1] != kSync1 || (p[2] != kSyncLong && p[2] != kSyncShort)) {
        return skip;
    }
    std::size_t total = 0;
    FrameKind kind = FrameKind::binary;
    if (p[2] == kSyncLong) {
        if (avail < 10) {
            return more;
        }
        const std::size_t header = p[3];
        const std::size_t body = le16(p + 8);
        if (header < limits_.min_header || header > limits_.max_header || body > limits_.max_binary_body) {
            ++counters_.bad_length;
            return skip;
        }
        total = header + body + kCrcBytes;
    } else {
        if (avail < 4) {
            return more;
        }
        kind = FrameKind::binary_short;
        total = kShortHeader + p[3] + kCrcBytes;
    }
    if (avail < total) {
        return more;
    }
    if (crc32(p, total - kCrcBytes) != le32(p + total - kCrcBytes)) {
        ++counters_.crc_errors;
        return skip;
    }
    return Candidate{Step::frame, kind, total, total};
}

StreamSplitter::Candidate StreamSplitter::try_text(const uint8_t* p, std::size_t avail, FrameKind kind,
                                                   std::size_t max_line, std::size_t digits)
{
    const Candidate skip{Step::skip, kind, 0, 1};
    // Resume validation where the previous feed stopped (a long line fed byte by byte).
    std::size_t i = text_checked_ > 0 ? text_checked_ : 1;
    for (; i < avail; ++i) {
        const uint8_t ch = p[i];
        if (ch == '*') {
            break;
        }
        if (!is_text(ch) || i > max_line) {
            return skip;
        }
    }
    if (i >= avail) {
        text_checked_ = i;
        return i > max_line ? skip : Candidate{Step::need_more, kind, 0, 0};
    }
    const std::size_t star = i;
    const std::size_t total = star + 1 + digits;
    if (avail < total) {
        text_checked_ = star;
        return Candidate{Step::need_more, kind, 0, 0};
    }
    uint32_t stated = 0;
    if (!parse_hex(p + star + 1, digits, stated)) {
        return skip;
    }
    const uint32_t actual = digits == 2 ? nmea_checksum(p + 1, star - 1) : crc32(p + 1, star - 1);
    if (actual != stated) {
        ++counters_.crc_errors;
        return skip;
    }
    return Candidate{Step::frame, kind, total, total};
}

StreamSplitter::Candidate StreamSplitter::try_reply(const uint8_t* p, std::size_t avail)
{
    std::size_t i = text_checked_ > 0 ? text_checked_ : 1;
    for (; i < avail; ++i) {
        const uint8_t ch = p[i];
        if (is_line_end(ch)) {
            return Candidate{Step::frame, FrameKind::reply, i, i};
        }
        if (!is_text(ch) || i > limits_.max_reply_line) {
            return Candidate{Step::skip, FrameKind::reply, 0, 1};
        }
    }
    text_checked_ = i;
    return Candidate{Step::need_more, FrameKind::reply, 0, 0};
}

StreamSplitter::Candidate StreamSplitter::try_prompt(const uint8_t* p, std::size_t avail)
{
    for (std::size_t i = 1; i < avail; ++i) {
        const uint8_t ch = p[i];
        if (ch == ']') {
            return i > 1 ? Candidate{Step::frame, FrameKind::prompt, i + 1, i + 1}
                         : Candidate{Step::skip, FrameKind::prompt, 0, 1};
        }
        const bool name_char = (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '_';
        if (!name_char || i >= limits_.max_prompt) {
            return Candidate{Step::skip, FrameKind::prompt, 0, 1};
        }
    }
    return Candidate{Step::need_more, FrameKind::prompt, 0, 0};
}

}  // namespace ugv::novatel
