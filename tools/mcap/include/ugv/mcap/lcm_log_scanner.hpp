// The events of an lcm-logger log, read from its bytes in memory (no I/O). A damaged stretch
// (bad sync word, impossible lengths, an event cut short) is skipped by searching for the
// next sync word whose event parses, so the events before and after it are kept.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace ugv::mcap {

struct LogEvent
{
    int64_t event_number = 0;
    int64_t utime = 0;  // the logger's receive time, us since the epoch
    std::string_view channel;
    const uint8_t* data = nullptr;
    std::size_t size = 0;
};

class LcmLogScanner
{
public:
    LcmLogScanner(const uint8_t* data, std::size_t size) : data_(data), size_(size) {}

    // The next event; false at the end of the bytes.
    bool next(LogEvent& event);

    std::size_t position() const { return pos_; }
    uint64_t skipped_bytes() const { return skipped_; }     // bytes in damaged stretches
    uint64_t damaged_stretches() const { return stretches_; }
    std::size_t first_damage() const { return first_damage_; }  // offset, when skipped_bytes() > 0

private:
    bool parse_at(std::size_t at, LogEvent& event, std::size_t& end) const;
    void skip(std::size_t from, std::size_t to);

    const uint8_t* data_;
    std::size_t size_;
    std::size_t pos_ = 0;
    uint64_t skipped_ = 0, stretches_ = 0;
    std::size_t first_damage_ = 0;
};

}  // namespace ugv::mcap
