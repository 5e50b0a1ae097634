#include "ugv/canopen/emcy.hpp"

#include "ugv/canopen/ids.hpp"

namespace ugv::canopen {

std::optional<Emergency> decode_emcy(const io::CanFrame& frame, uint8_t node)
{
    // An EMCY always carries 8 bytes; a 0-byte frame on 0x080 is SYNC, not EMCY (node 0).
    if (frame.id != kEmcyBase + node || node == 0 || frame.extended || frame.rtr || frame.dlc != 8)
        return std::nullopt;
    Emergency e;
    e.error_code = static_cast<uint16_t>(frame.data[0] | (frame.data[1] << 8));
    e.error_register = frame.data[2];
    for (std::size_t i = 0; i < 5; ++i) e.manufacturer[i] = frame.data[3 + i];
    return e;
}

io::CanFrame encode_emcy(uint8_t node, const Emergency& e)
{
    io::CanFrame f;
    f.id = kEmcyBase + node;
    f.dlc = 8;
    f.data[0] = static_cast<uint8_t>(e.error_code & 0xFF);
    f.data[1] = static_cast<uint8_t>(e.error_code >> 8);
    f.data[2] = e.error_register;
    for (std::size_t i = 0; i < 5; ++i) f.data[3 + i] = e.manufacturer[i];
    return f;
}

const char* describe_emcy(uint16_t code)
{
    // Specific codes first (CiA 301 / CiA 402), then the class in the high nibble(s).
    switch (code) {
    case 0x0000: return "error reset / no error";
    case 0x8110: return "CAN overrun (objects lost)";
    case 0x8120: return "CAN in error passive mode";
    case 0x8130: return "life guard or heartbeat error";
    case 0x8140: return "recovered from bus off";
    case 0x8611: return "following error";
    case 0x7300: return "sensor (encoder) error";
    case 0x4310: return "drive temperature too high";
    case 0x2310: return "continuous over-current";
    case 0x3210: return "DC link over-voltage";
    case 0x3220: return "DC link under-voltage";
    default: break;
    }
    switch (code >> 12) {
    case 0x1: return "generic error";
    case 0x2: return "current";
    case 0x3: return "voltage";
    case 0x4: return "temperature";
    case 0x5: return "device hardware";
    case 0x6: return "device software";
    case 0x7: return "additional modules";
    case 0x8: return "monitoring";
    case 0x9: return "external error";
    case 0xF: return "device specific";
    default: return "unknown error class";
    }
}

}  // namespace ugv::canopen
