// Emergency (EMCY) messages: COB-ID 0x80 + node, `[code lo, code hi, error register, 5 bytes
// manufacturer-specific]`. Error code 0x0000 means "error reset / no error".
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "ugv/io/can_frame.hpp"

namespace ugv::canopen {

struct Emergency
{
    uint16_t error_code = 0;       // CiA 301 / CiA 402 error code (0x603F mirrors it)
    uint8_t error_register = 0;    // object 0x1001
    std::array<uint8_t, 5> manufacturer{};
    bool is_reset() const { return error_code == 0; }
};

std::optional<Emergency> decode_emcy(const io::CanFrame& frame, uint8_t node);
io::CanFrame encode_emcy(uint8_t node, const Emergency& emcy);
// The error class of a code ("current", "voltage", "following error", ...), for logs.
const char* describe_emcy(uint16_t error_code);

}  // namespace ugv::canopen
