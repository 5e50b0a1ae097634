#include "ugv/novatel/checksum.hpp"

#include <array>

namespace ugv::novatel {
namespace {

// Slicing-by-8 tables: table[k][b] is the CRC of byte b followed by k zero bytes, so eight
// input bytes are folded per step instead of one (the decoder's throughput is CRC-bound).
using Tables = std::array<std::array<uint32_t, 256>, 8>;

constexpr Tables make_tables()
{
    Tables t{};
    for (uint32_t b = 0; b < 256; ++b) {
        uint32_t c = b;
        for (int k = 0; k < 8; ++k) {
            c = (c & 1U) ? (c >> 1) ^ 0xEDB88320U : c >> 1;
        }
        t[0][b] = c;
    }
    for (std::size_t k = 1; k < 8; ++k) {
        for (uint32_t b = 0; b < 256; ++b) {
            const uint32_t prev = t[k - 1][b];
            t[k][b] = (prev >> 8) ^ t[0][prev & 0xFFU];
        }
    }
    return t;
}

constexpr Tables kTables = make_tables();

inline uint32_t load_le32(const uint8_t* p)
{
    return static_cast<uint32_t>(p[0]) | static_cast<uint32_t>(p[1]) << 8 | static_cast<uint32_t>(p[2]) << 16 |
           static_cast<uint32_t>(p[3]) << 24;
}

}  // namespace

uint32_t crc32(const uint8_t* data, std::size_t n, uint32_t crc)
{
    const auto& t = kTables;
    while (n >= 8) {
        const uint32_t lo = load_le32(data) ^ crc;
        const uint32_t hi = load_le32(data + 4);
        crc = t[7][lo & 0xFFU] ^ t[6][(lo >> 8) & 0xFFU] ^ t[5][(lo >> 16) & 0xFFU] ^ t[4][lo >> 24] ^
              t[3][hi & 0xFFU] ^ t[2][(hi >> 8) & 0xFFU] ^ t[1][(hi >> 16) & 0xFFU] ^ t[0][hi >> 24];
        data += 8;
        n -= 8;
    }
    while (n-- > 0) {
        crc = (crc >> 8) ^ t[0][(crc ^ *data++) & 0xFFU];
    }
    return crc;
}

uint8_t nmea_checksum(const uint8_t* data, std::size_t n)
{
    uint8_t x = 0;
    for (std::size_t i = 0; i < n; ++i) {
        x = static_cast<uint8_t>(x ^ data[i]);
    }
    return x;
}

bool parse_hex(const uint8_t* text, std::size_t n, uint32_t& value)
{
    uint32_t v = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const uint8_t c = text[i];
        uint32_t d = 0;
        if (c >= '0' && c <= '9') {
            d = static_cast<uint32_t>(c - '0');
        } else if (c >= 'a' && c <= 'f') {
            d = static_cast<uint32_t>(c - 'a' + 10);
        } else if (c >= 'A' && c <= 'F') {
            d = static_cast<uint32_t>(c - 'A' + 10);
        } else {
            return false;
        }
        v = (v << 4) | d;
    }
    value = v;
    return true;
}

}  // namespace ugv::novatel
