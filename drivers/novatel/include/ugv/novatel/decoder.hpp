// The receiver-stream decoder: StreamSplitter + the per-framing log decoders, with the
// counters a daemon reports. Pure: bytes and their arrival times in, messages out.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>

#include "ugv/novatel/log_decoding.hpp"
#include "ugv/novatel/messages.hpp"
#include "ugv/novatel/stream_splitter.hpp"

namespace ugv::novatel {

// Valid only during the sink call (the message is the decoder's scratch).
struct Decoded
{
    const Message& message;
    FrameKind kind;
    // When the frame's last byte arrived (us since the epoch): the chunk's time stamp minus
    // the transmission time of the bytes that followed the frame in the same chunk, so a
    // batch of frames read at once does not share one stamp.
    int64_t arrival_utime;
    std::size_t frame_bytes;  // the frame's size on the wire (for its transmission time)
};

struct DecoderCounters
{
    uint64_t decoded = 0;             // messages handed out (logs, sentences, replies)
    uint64_t binary_responses = 0;    // binary replies to commands
    uint64_t malformed = 0;           // valid checksum, but a body we could not read
    uint64_t unknown_total = 0;
    std::map<uint16_t, uint64_t> unknown_binary_ids;   // binary logs we skip, by message id
    std::map<std::string, uint64_t> unknown_names;     // ASCII logs / NMEA sentences we skip

    // The logs skipped are named as they are met: unknown_id_<id> and unknown_<name>.
    template <class F>
    void visit(F&& f) const
    {
        f("decoded", decoded);
        f("binary_responses", binary_responses);
        f("malformed", malformed);
        f("unknown_ids", unknown_total);
        for (const auto& [id, n] : unknown_binary_ids) f("unknown_id_" + std::to_string(id), n);
        for (const auto& [name, n] : unknown_names) f("unknown_" + name, n);
    }
};

class Decoder
{
public:
    using Sink = std::function<void(const Decoded&)>;

    explicit Decoder(SplitterLimits limits = {}) : splitter_(limits) {}

    // Line speed of the port, for the per-frame arrival correction (0 = no correction).
    void set_baud(int baud) { baud_ = baud; }
    // chunk_utime: when the chunk arrived (the read's time stamp).
    void feed(const uint8_t* data, std::size_t n, int64_t chunk_utime, const Sink& sink);
    void reset() { splitter_.reset(); }

    const SplitterCounters& splitter_counters() const { return splitter_.counters(); }
    const DecoderCounters& counters() const { return counters_; }

private:
    void on_frame(const FrameView& frame, uint64_t chunk_end, int64_t chunk_utime, const Sink& sink);

    StreamSplitter splitter_;
    DecoderCounters counters_;
    int baud_ = 0;
    Message scratch_;
};

}  // namespace ugv::novatel
