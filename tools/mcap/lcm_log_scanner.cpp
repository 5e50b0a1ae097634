#include "ugv/mcap/lcm_log_scanner.hpp"

namespace ugv::mcap {
namespace {

constexpr uint32_t kSync = 0xEDA1DA01;       // lcm-logger's event sync word (big-endian)
constexpr std::size_t kHeader = 4 + 8 + 8 + 4 + 4;
constexpr int64_t kMaxChannel = 255;         // LCM allows 63; anything beyond is damage

uint64_t be(const uint8_t* p, int bytes)
{
    uint64_t v = 0;
    for (int k = 0; k < bytes; ++k) v = (v << 8) | p[k];
    return v;
}

}  // namespace

bool LcmLogScanner::parse_at(std::size_t at, LogEvent& event, std::size_t& end) const
{
    if (size_ - at < kHeader) return false;
    const uint8_t* p = data_ + at;
    if (be(p, 4) != kSync) return false;
    const auto channel_len = static_cast<int32_t>(be(p + 20, 4));
    const auto data_len = static_cast<int32_t>(be(p + 24, 4));
    if (channel_len < 1 || channel_len > kMaxChannel || data_len < 0) return false;
    const std::size_t total = kHeader + static_cast<std::size_t>(channel_len) + static_cast<std::size_t>(data_len);
    if (total > size_ - at) return false;  // cut short
    event.event_number = static_cast<int64_t>(be(p + 4, 8));
    event.utime = static_cast<int64_t>(be(p + 12, 8));
    event.channel = std::string_view(reinterpret_cast<const char*>(p + kHeader), static_cast<std::size_t>(channel_len));
    event.data = p + kHeader + channel_len;
    event.size = static_cast<std::size_t>(data_len);
    end = at + total;
    return true;
}

void LcmLogScanner::skip(std::size_t from, std::size_t to)
{
    if (to <= from) return;
    if (skipped_ == 0) first_damage_ = from;
    skipped_ += to - from;
    ++stretches_;
}

bool LcmLogScanner::next(LogEvent& event)
{
    if (pos_ >= size_) return false;
    std::size_t end = 0;
    if (parse_at(pos_, event, end)) {
        pos_ = end;
        return true;
    }
    // Damage: the next sync word whose event parses starts the good data again.
    for (std::size_t at = pos_ + 1; at + kHeader <= size_; ++at) {
        if (data_[at] != 0xED || !parse_at(at, event, end)) continue;
        skip(pos_, at);
        pos_ = end;
        return true;
    }
    skip(pos_, size_);
    pos_ = size_;
    return false;
}

}  // namespace ugv::mcap
