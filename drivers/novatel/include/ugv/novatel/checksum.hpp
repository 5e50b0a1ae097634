// Checksums of the three framings a NovAtel OEM4-class receiver sends.
#pragma once

#include <cstddef>
#include <cstdint>

namespace ugv::novatel {

// NovAtel CRC-32: reflected polynomial 0xEDB88320, initial value 0, no final XOR.
// Used by binary logs (over header + body) and by ASCII logs (over the text between
// '#'/'%' and '*'). `crc` continues a previous computation (0 to start).
uint32_t crc32(const uint8_t* data, std::size_t n, uint32_t crc = 0);

// NMEA 0183: XOR of the bytes between '$' and '*'.
uint8_t nmea_checksum(const uint8_t* data, std::size_t n);

// Parses exactly n hex digits (either case) into value. False on any non-hex digit.
bool parse_hex(const uint8_t* text, std::size_t n, uint32_t& value);

}  // namespace ugv::novatel
