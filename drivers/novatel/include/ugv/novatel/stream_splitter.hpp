// Splits the byte stream of one receiver port into frames. A NovAtel port really carries a
// mix: binary logs (long header AA 44 12, short header AA 44 13), ASCII logs (#...*crc32 and
// short %...*crc32), NMEA 0183 sentences ($...*hh), command replies (<OK, <ERROR:...,
// abbreviated ASCII lines <...) and port prompts ([COM1], [ICOM1], [USB1]).
//
// Bytes arrive in chunks of any size and split. Anything that is not a frame with a valid
// checksum is skipped one byte at a time (resynchronising on the next frame start), so a
// corrupted length field costs at most the bounded frame length, never a stall. Frames are
// handed out as views into the splitter's buffer, valid only during the callback.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace ugv::novatel {

enum class FrameKind : uint8_t {
    binary,        // AA 44 12, long header (length in byte 3), body, CRC-32
    binary_short,  // AA 44 13, 12-byte header, body, CRC-32
    ascii,         // #NAME,...;...*xxxxxxxx
    ascii_short,   // %NAME,...;...*xxxxxxxx
    nmea,          // $TALKER...*hh
    reply,         // a line starting with '<': <OK, <ERROR:..., abbreviated ASCII output
    prompt,        // [COM1], [ICOM1], [USB2] ...
};
inline constexpr std::size_t kFrameKindCount = 7;
const char* frame_kind_name(FrameKind kind);

struct FrameView
{
    FrameKind kind;
    const uint8_t* data;   // binary: sync .. CRC; text: '#'/'%'/'$' .. last checksum digit;
    std::size_t size;      // reply/prompt: the line without CR/LF
    uint64_t end_offset;   // stream offset one past the frame's last byte (bytes fed before it)
};

struct SplitterLimits
{
    std::size_t max_binary_body = 4096;  // bytes; a longer length field is taken as corrupt
    std::size_t min_header = 28;         // long-header length field bounds (OEM4 sends 28;
    std::size_t max_header = 64;         //  later receivers may grow it: trust the field)
    std::size_t max_ascii_line = 8192;   // bytes from '#' to '*'
    std::size_t max_nmea_line = 256;     // NMEA says 82; proprietary sentences are longer
    std::size_t max_reply_line = 8192;
    std::size_t max_prompt = 16;
};

struct SplitterCounters
{
    std::array<uint64_t, kFrameKindCount> frames{};  // valid frames by kind
    uint64_t crc_errors = 0;     // complete frames whose checksum did not match
    uint64_t bad_length = 0;     // binary headers with an out-of-bounds length field
    uint64_t resyncs = 0;        // runs of skipped bytes (one per loss of sync)
    uint64_t skipped_bytes = 0;  // bytes that belonged to no valid frame (CR/LF excluded)
    uint64_t frames_total() const;

    template <class F>
    void visit(F&& f) const
    {
        for (std::size_t k = 0; k < kFrameKindCount; ++k)
            f(std::string("frames_") + frame_kind_name(static_cast<FrameKind>(k)), frames[k]);
        f("crc_errors", crc_errors);
        f("bad_length", bad_length);
        f("resyncs", resyncs);
        f("skipped_bytes", skipped_bytes);
    }
};

class StreamSplitter
{
public:
    using Sink = std::function<void(const FrameView&)>;

    explicit StreamSplitter(SplitterLimits limits = {}) : limits_(limits) {}

    // Feeds n bytes; calls sink once per complete valid frame, in stream order.
    void feed(const uint8_t* data, std::size_t n, const Sink& sink);
    // Forgets a partial frame (after a reopen, the old bytes cannot continue).
    void reset();

    const SplitterCounters& counters() const { return counters_; }
    uint64_t bytes_fed() const { return fed_; }
    std::size_t buffered() const { return buf_.size(); }

private:
    enum class Step { frame, skip, need_more };
    struct Candidate
    {
        Step step;
        FrameKind kind;
        std::size_t size;      // frame bytes handed to the sink
        std::size_t consumed;  // bytes consumed (size plus a reply's line end)
    };

    // Scans [data, data+n) (stream offset base) and returns the bytes consumed.
    std::size_t scan(const uint8_t* data, std::size_t n, uint64_t base, const Sink& sink);
    Candidate try_binary(const uint8_t* p, std::size_t avail);
    Candidate try_text(const uint8_t* p, std::size_t avail, FrameKind kind, std::size_t max_line,
                       std::size_t digits);
    Candidate try_reply(const uint8_t* p, std::size_t avail);
    Candidate try_prompt(const uint8_t* p, std::size_t avail);
    void skip_byte();

    SplitterLimits limits_;
    SplitterCounters counters_;
    std::vector<uint8_t> buf_;  // unconsumed tail: a partial frame
    uint64_t fed_ = 0;          // bytes fed so far
    std::size_t text_checked_ = 0;  // bytes of a pending text frame already validated
    bool in_garbage_ = false;
};

}  // namespace ugv::novatel
