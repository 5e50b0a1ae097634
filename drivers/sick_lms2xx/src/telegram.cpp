#include "ugv/sick_lms2xx/telegram.hpp"

#include <stdexcept>

#include "ugv/sick_lms2xx/crc.hpp"

namespace ugv::sick_lms2xx {

std::vector<uint8_t> encode_telegram(uint8_t address, uint8_t command, std::span<const uint8_t> data,
                                     const uint8_t* status)
{
    const std::size_t len = 1 + data.size() + (status != nullptr ? 1 : 0);
    if (len > kMaxLen) throw std::invalid_argument("sick_lms2xx: telegram payload longer than 812 bytes");
    std::vector<uint8_t> out;
    out.reserve(kHeaderBytes + len + kCrcBytes);
    out.push_back(kStx);
    out.push_back(address);
    put_u16le(out, static_cast<uint16_t>(len));
    out.push_back(command);
    out.insert(out.end(), data.begin(), data.end());
    if (status != nullptr) out.push_back(*status);
    put_u16le(out, crc16(out.data(), out.size()));
    return out;
}

}  // namespace ugv::sick_lms2xx
