#include "ugv/microstrain_gx1/frame_parser.hpp"

#include <cmath>

namespace ugv::microstrain_gx1 {

FrameParser::FrameParser(double byte_period_us) : byte_period_us_(byte_period_us)
{
    accept_all();
    buf_.reserve(4096);
}

void FrameParser::accept_only(std::initializer_list<uint8_t> commands)
{
    accepted_.fill(false);
    for (uint8_t c : commands) accepted_[c] = is_command(c);
}

void FrameParser::accept_all()
{
    for (std::size_t b = 0; b < accepted_.size(); ++b) accepted_[b] = is_command(static_cast<uint8_t>(b));
}

void FrameParser::feed(const uint8_t* data, std::size_t n, int64_t arrival_utime)
{
    if (n == 0) return;
    compact();
    buf_.insert(buf_.end(), data, data + n);
    chunks_.push_back({head_offset_ + (buf_.size() - head_), arrival_utime});
}

void FrameParser::clear()
{
    head_offset_ += buf_.size() - head_;
    buf_.clear();
    head_ = 0;
    chunks_.clear();
    in_step_ = true;
}

void FrameParser::compact()
{
    // Moving the unread tail to the front is cheap (it is at most one partial frame plus
    // the chunk not parsed yet); doing it only when the head is far in keeps it rare.
    if (head_ == 0) return;
    if (head_ == buf_.size()) {
        buf_.clear();
        head_ = 0;
    } else if (head_ >= 4096) {
        buf_.erase(buf_.begin(), buf_.begin() + static_cast<std::ptrdiff_t>(head_));
        head_ = 0;
    }
}

void FrameParser::skip_one()
{
    if (in_step_) {
        ++counters_.resyncs;
        in_step_ = false;
    }
    ++counters_.bytes_skipped;
    ++head_;
    ++head_offset_;
}

int64_t FrameParser::byte_utime(uint64_t offset)
{
    while (!chunks_.empty() && chunks_.front().end_offset <= offset) chunks_.pop_front();
    if (chunks_.empty()) return 0;
    const Chunk& c = chunks_.front();
    const double later_bytes = static_cast<double>(c.end_offset - 1 - offset);
    return c.utime - static_cast<int64_t>(std::llround(later_bytes * byte_period_us_));
}

bool FrameParser::verifies_at(std::size_t pos) const
{
    const uint8_t b = buf_[pos];
    const std::size_t len = reply_length(b);
    if (!accepted_[b] || buf_.size() - pos < len) return false;
    const uint8_t* p = buf_.data() + pos;
    return checksum(b, p + 1, (len - 3) / 2) == static_cast<uint16_t>(p[len - 2] << 8 | p[len - 1]);
}

bool FrameParser::next(Frame& out)
{
    while (head_ < buf_.size()) {
        const uint8_t b = buf_[head_];
        if (!accepted_[b]) {
            skip_one();
            continue;
        }
        const std::size_t len = reply_length(b);
        if (buf_.size() - head_ < len) {
            // The candidate is incomplete. If a complete frame verifies further on, the
            // candidate was a false start (e.g. a long command's byte in a checksum) and
            // would only delay that frame: move on to it now.
            std::size_t later = head_ + 1;
            while (later < buf_.size() && !verifies_at(later)) ++later;
            if (later == buf_.size()) return false;  // wait for the rest of the candidate
            while (head_ < later) skip_one();
            continue;
        }
        const uint8_t* p = buf_.data() + head_;
        const std::size_t nwords = (len - 3) / 2;
        if (!verifies_at(head_)) {
            if (in_step_) ++counters_.checksum_errors;
            skip_one();
            continue;
        }
        out.command = b;
        out.nwords = nwords;
        for (std::size_t i = 0; i < nwords; ++i)
            out.words[i] = static_cast<uint16_t>(p[1 + 2 * i] << 8 | p[2 + 2 * i]);
        out.first_byte_utime = byte_utime(head_offset_);
        head_ += len;
        head_offset_ += len;
        in_step_ = true;
        ++counters_.frames;
        return true;
    }
    return false;
}

}  // namespace ugv::microstrain_gx1
