// Frame -> message for the three framings. Each function takes one complete frame whose
// checksum the splitter already verified and fills `out` when the frame is a log or
// sentence we decode.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "ugv/novatel/messages.hpp"

namespace ugv::novatel {

enum class DecodeStatus {
    decoded,    // out holds the message
    response,   // a binary reply to a command (message-type bit 7): nothing to decode
    unknown,    // a valid log or sentence that we do not decode: skip and count it
    malformed,  // a log we decode whose body is too short or whose fields do not parse
};

// Binary frame (long or short header), sync to CRC. `id` receives the message id.
DecodeStatus decode_binary(const uint8_t* frame, std::size_t size, FrameKind kind, Message& out, uint16_t& id);

// ASCII log ('#' or '%' to the last CRC digit). `name` receives the log name as sent
// (e.g. "BESTPOSA").
DecodeStatus decode_ascii(const uint8_t* frame, std::size_t size, FrameKind kind, Message& out,
                          std::string_view& name);

// NMEA sentence ('$' to the last checksum digit). `address` receives e.g. "GPGGA".
DecodeStatus decode_nmea(const uint8_t* frame, std::size_t size, Message& out, std::string_view& address);

}  // namespace ugv::novatel
