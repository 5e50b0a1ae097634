// The SICK LMS 2xx telegram checksum: a CRC-16 (polynomial 0x8005, start 0) that folds the
// previous byte into each step. It covers every byte from STX through the last DATA/STATUS
// byte; the result is sent least significant byte first.
#pragma once

#include <cstddef>
#include <cstdint>

namespace ugv::sick_lms2xx {

uint16_t crc16(const uint8_t* data, std::size_t n);

}  // namespace ugv::sick_lms2xx
