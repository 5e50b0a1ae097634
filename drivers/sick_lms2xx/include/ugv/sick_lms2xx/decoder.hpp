// A streaming telegram decoder: feed it byte chunks of any size and split; it reports the
// ACK/NAK bytes seen between telegrams, every telegram whose CRC is right, and every frame it
// had to reject. It never reports a telegram with a bad CRC or a LEN above 812; after a bad
// frame it resynchronises by searching for the next STX + ADDR pair (`02 80` on the host
// side) starting one byte after the rejected STX, so a good telegram hidden inside garbage
// is still found.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "ugv/sick_lms2xx/telegram.hpp"

namespace ugv::sick_lms2xx {

struct DecoderStats
{
    uint64_t bytes_in = 0;
    uint64_t telegrams = 0;       // good telegrams delivered
    uint64_t crc_errors = 0;      // frames with a bad CRC (dropped)
    uint64_t length_errors = 0;   // headers with LEN 0 or > 812 (dropped)
    uint64_t resyncs = 0;         // runs of bytes skipped to find the next frame start
    uint64_t skipped_bytes = 0;   // bytes that belonged to no telegram (ACK/NAK excluded)
};

struct DecoderEvent
{
    enum class Kind {
        ack,        // a 0x06 byte between telegrams
        nak,        // a 0x15 byte between telegrams
        telegram,   // a good telegram
        bad_crc,    // a complete frame whose CRC did not match (the device answers these with NAK)
    };
    Kind kind = Kind::telegram;
    Telegram telegram;  // for telegram (and, with the received bytes, bad_crc)
};

class Decoder
{
public:
    using Handler = std::function<void(const DecoderEvent&)>;

    // address: the ADDR byte of the telegrams to accept (kDeviceAddress on the host side,
    // kHostAddress in a device emulator). Replies carry a STATUS byte, requests do not.
    explicit Decoder(uint8_t address = kDeviceAddress);

    void feed(const uint8_t* data, std::size_t n, const Handler& handler);
    // Forgets any partial frame (after a baud change, or when the line is known to be garbage).
    void reset();
    const DecoderStats& stats() const { return stats_; }
    std::size_t buffered() const { return buf_.size() - pos_; }

private:
    void process(const Handler& handler);
    void skip(std::size_t n, bool count_resync);

    uint8_t address_;
    bool has_status_;
    std::vector<uint8_t> buf_;
    std::size_t pos_ = 0;        // first unprocessed byte in buf_
    bool skipping_ = false;      // inside a run of skipped bytes (one resync per run)
    DecoderStats stats_;
};

}  // namespace ugv::sick_lms2xx
