// Byte stream -> verified 3DM-GX1 replies, for chunks of any split.
//
// The command byte that starts a reply also occurs inside payloads, so the parser never
// trusts a start byte: it waits for the whole reply length, checks the checksum, and on a
// mismatch slides forward by ONE byte (a good frame may start inside the bad candidate).
// A frame whose checksum fails is never returned. An incomplete candidate does not hold back
// a complete frame that verifies after it (a false start of a longer reply).
//
// Counters:
//   frames          replies returned
//   checksum_errors candidates that failed the checksum where a frame was expected (right
//                   after a good frame, or at the start): a damaged frame, not garbage
//   resyncs         times the parser lost step and had to hunt for the next frame
//   bytes_skipped   bytes discarded while hunting
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <initializer_list>
#include <vector>

#include "ugv/microstrain_gx1/protocol.hpp"

namespace ugv::microstrain_gx1 {

struct Frame
{
    uint8_t command = 0;
    std::size_t nwords = 0;
    std::array<uint16_t, max_reply_words> words{};  // the data words, big-endian decoded
    // Host time (us since the epoch) the first byte of the frame arrived, estimated from the
    // arrival time of its chunk minus the transmission time of the bytes after it.
    int64_t first_byte_utime = 0;

    int16_t word_signed(std::size_t i) const { return static_cast<int16_t>(words[i]); }
    // The device timer (last data word); only meaningful when reply_has_ticks(command).
    uint16_t ticks() const { return nwords == 0 ? 0 : words[nwords - 1]; }
};

struct ParserCounters
{
    uint64_t frames = 0;
    uint64_t checksum_errors = 0;
    uint64_t resyncs = 0;
    uint64_t bytes_skipped = 0;

    template <class F>
    void visit(F&& f) const
    {
        f("frames", frames);
        f("checksum_errors", checksum_errors);
        f("resyncs", resyncs);
        f("bytes_skipped", bytes_skipped);
    }
};

class FrameParser
{
public:
    // byte_period_us: transmission time of one byte (10 bits / baud), used to date first bytes.
    explicit FrameParser(double byte_period_us = 0.0);

    // Only these commands start a frame (the session knows what it asked for); fewer false
    // starts in payload bytes. Default: every command of the protocol.
    void accept_only(std::initializer_list<uint8_t> commands);
    void accept_all();
    void set_byte_period_us(double us) { byte_period_us_ = us; }

    // Appends a chunk received at arrival_utime (time its last byte was read).
    void feed(const uint8_t* data, std::size_t n, int64_t arrival_utime = 0);
    // The next verified frame, if the buffer holds one. Call until it returns false.
    bool next(Frame& out);
    // Drops buffered bytes (after a flush or reconnect); counters are kept.
    void clear();

    const ParserCounters& counters() const { return counters_; }
    std::size_t buffered() const { return buf_.size() - head_; }

private:
    struct Chunk
    {
        uint64_t end_offset;  // stream offset one past the chunk's last byte
        int64_t utime;
    };
    void skip_one();
    bool verifies_at(std::size_t pos) const;
    int64_t byte_utime(uint64_t offset);
    void compact();

    std::array<bool, 256> accepted_{};
    double byte_period_us_;
    std::vector<uint8_t> buf_;
    std::size_t head_ = 0;
    uint64_t head_offset_ = 0;  // stream offset of buf_[head_]
    std::deque<Chunk> chunks_;
    bool in_step_ = true;
    ParserCounters counters_;
};

}  // namespace ugv::microstrain_gx1
