#include "json_out.hpp"

#include <array>
#include <cstring>

#include "ugv/reflect.hpp"

namespace ugv::foxglove::detail {

JsonOut& JsonOut::string(std::string_view s)
{
    sep();
    out_ += reflect::json_quote(s);
    return *this;
}

JsonOut& JsonOut::base64(const uint8_t* data, std::size_t size)
{
    static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    // Two characters per 12 bits from one table: half the lookups (the grids are megabytes).
    static const auto kPairs = [] {
        std::array<char, 2 * 4096> t{};
        for (std::size_t v = 0; v < 4096; ++v) {
            t[2 * v] = kAlphabet[v >> 6];
            t[2 * v + 1] = kAlphabet[v & 63];
        }
        return t;
    }();
    sep();
    out_ += '"';
    const std::size_t start = out_.size();
    out_.resize(start + 4 * ((size + 2) / 3));
    char* o = out_.data() + start;
    std::size_t i = 0;
    for (; i + 3 <= size; i += 3) {
        const uint32_t v = (uint32_t{data[i]} << 16) | (uint32_t{data[i + 1]} << 8) | data[i + 2];
        std::memcpy(o, &kPairs[2 * (v >> 12)], 2);
        std::memcpy(o + 2, &kPairs[2 * (v & 4095)], 2);
        o += 4;
    }
    if (i < size) {
        const uint32_t v = (uint32_t{data[i]} << 16) | (i + 1 < size ? uint32_t{data[i + 1]} << 8 : 0u);
        *o++ = kAlphabet[v >> 18];
        *o++ = kAlphabet[(v >> 12) & 63];
        *o++ = i + 1 < size ? kAlphabet[(v >> 6) & 63] : '=';
        *o++ = '=';
    }
    out_ += '"';
    return *this;
}

JsonOut& JsonOut::time_us(int64_t utime)
{
    // Foxglove times are unsigned: a time before the epoch is clamped to 0.
    const int64_t t = utime < 0 ? 0 : utime;
    begin_object().key("sec").integer(t / 1000000).key("nsec").integer((t % 1000000) * 1000).end_object();
    return *this;
}

}  // namespace ugv::foxglove::detail
