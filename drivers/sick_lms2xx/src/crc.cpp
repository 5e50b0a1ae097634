#include "ugv/sick_lms2xx/crc.hpp"

namespace ugv::sick_lms2xx {

uint16_t crc16(const uint8_t* data, std::size_t n)
{
    // Kept in 32 bits and masked once per step: the shift and the conditional xor are
    // branch-free, which is what makes the decoder fast on long scan telegrams.
    uint32_t crc = 0;
    uint32_t prev = 0;
    for (std::size_t i = 0; i < n; ++i) {
        const uint32_t b = data[i];
        const uint32_t poly = (crc & 0x8000u) ? 0x8005u : 0u;
        crc = ((crc << 1) & 0xfffeu) ^ poly;
        crc ^= b | (prev << 8);
        prev = b;
    }
    return static_cast<uint16_t>(crc);
}

}  // namespace ugv::sick_lms2xx
