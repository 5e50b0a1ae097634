#include "ugv/sick_lms2xx/decoder.hpp"

#include <cstring>

#include "ugv/sick_lms2xx/crc.hpp"

namespace ugv::sick_lms2xx {

Decoder::Decoder(uint8_t address) : address_(address), has_status_(address == kDeviceAddress)
{
    buf_.reserve(4096);
}

void Decoder::reset()
{
    buf_.clear();
    pos_ = 0;
    skipping_ = false;
}

void Decoder::feed(const uint8_t* data, std::size_t n, const Handler& handler)
{
    stats_.bytes_in += n;
    // Compact first so the buffer does not grow without bound; one move per chunk.
    if (pos_ > 0) {
        buf_.erase(buf_.begin(), buf_.begin() + static_cast<std::ptrdiff_t>(pos_));
        pos_ = 0;
    }
    buf_.insert(buf_.end(), data, data + n);
    process(handler);
}

void Decoder::skip(std::size_t n, bool count_resync)
{
    if (n == 0) return;
    if (count_resync && !skipping_) {
        ++stats_.resyncs;
        skipping_ = true;
    }
    if (count_resync) stats_.skipped_bytes += n;
    pos_ += n;
}

void Decoder::process(const Handler& handler)
{
    const uint8_t* const base = buf_.data();
    const std::size_t end = buf_.size();
    DecoderEvent ev;
    while (pos_ < end) {
        const uint8_t b = base[pos_];
        if (b != kStx) {
            // Between telegrams: an ACK/NAK byte is an answer; anything else is garbage up to
            // the next STX.
            if (!skipping_ && (b == kAck || b == kNak)) {
                ev.kind = b == kAck ? DecoderEvent::Kind::ack : DecoderEvent::Kind::nak;
                ev.telegram = Telegram{};
                ++pos_;
                handler(ev);
                continue;
            }
            const void* stx = std::memchr(base + pos_, kStx, end - pos_);
            const std::size_t next = stx ? static_cast<std::size_t>(static_cast<const uint8_t*>(stx) - base) : end;
            skip(next - pos_, true);
            continue;
        }
        if (end - pos_ < 2) return;  // wait for the ADDR byte
        if (base[pos_ + 1] != address_) {
            skip(1, true);
            continue;
        }
        if (end - pos_ < kHeaderBytes) return;
        const std::size_t len = get_u16le(base + pos_ + 2);
        const std::size_t min_len = has_status_ ? 2 : 1;  // CMD (+ STATUS)
        if (len < min_len || len > kMaxLen) {
            ++stats_.length_errors;
            skip(1, true);
            continue;
        }
        const std::size_t total = kHeaderBytes + len + kCrcBytes;
        if (end - pos_ < total) return;  // wait for the rest of the frame
        const uint8_t* f = base + pos_;
        const uint16_t want = get_u16le(f + kHeaderBytes + len);
        Telegram& t = ev.telegram;
        t.address = f[1];
        t.command = f[kHeaderBytes];
        t.has_status = has_status_;
        t.status = has_status_ ? f[kHeaderBytes + len - 1] : 0;
        t.data = std::span<const uint8_t>(f + kHeaderBytes + 1, len - min_len);
        t.raw = std::span<const uint8_t>(f, total);
        if (crc16(f, kHeaderBytes + len) != want) {
            ++stats_.crc_errors;
            ev.kind = DecoderEvent::Kind::bad_crc;
            handler(ev);
            // The STX may have been a data byte: look for a frame start inside this one.
            skip(1, true);
            continue;
        }
        skipping_ = false;
        ++stats_.telegrams;
        ev.kind = DecoderEvent::Kind::telegram;
        pos_ += total;
        handler(ev);
    }
}

}  // namespace ugv::sick_lms2xx
