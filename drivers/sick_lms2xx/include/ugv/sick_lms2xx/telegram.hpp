// Telegram framing of the SICK LMS 2xx serial protocol:
//   STX(0x02) | ADDR | LEN (u16 LE) | CMD | DATA... | [STATUS] | CRC (u16 LE)
// Requests (host -> LMS) use ADDR 0x00 and LEN counts CMD + DATA; replies (LMS -> host) use
// ADDR 0x80 and LEN also counts the trailing STATUS byte. Each request is answered first by
// one byte, ACK (0x06) or NAK (0x15), then by the reply telegram whose CMD is the request's
// CMD + 0x80.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace ugv::sick_lms2xx {

inline constexpr uint8_t kStx = 0x02;
inline constexpr uint8_t kHostAddress = 0x00;    // ADDR of a request
inline constexpr uint8_t kDeviceAddress = 0x80;  // ADDR of a reply
inline constexpr uint8_t kAck = 0x06;
inline constexpr uint8_t kNak = 0x15;
// The largest LEN the device sends; anything larger is garbage to resynchronise past.
inline constexpr std::size_t kMaxLen = 812;
inline constexpr std::size_t kHeaderBytes = 4;  // STX ADDR LEN LEN
inline constexpr std::size_t kCrcBytes = 2;
inline constexpr uint8_t kReplyBit = 0x80;      // reply CMD = request CMD | 0x80

// Command bytes (requests) and their replies.
namespace cmd {
inline constexpr uint8_t reset = 0x10;
inline constexpr uint8_t switch_mode = 0x20;     // operating mode: baud, installation, streaming
inline constexpr uint8_t status = 0x31;
inline constexpr uint8_t type = 0x3A;
inline constexpr uint8_t variant = 0x3B;
inline constexpr uint8_t read_config = 0x74;
inline constexpr uint8_t write_config = 0x77;
inline constexpr uint8_t scan = 0xB0;            // scan data (a reply-direction telegram)
inline constexpr uint8_t reset_reply = 0x91;
inline constexpr uint8_t power_on = 0x90;        // sent by the device after a reset
}  // namespace cmd

inline constexpr uint8_t reply_command(uint8_t request_command) { return static_cast<uint8_t>(request_command | kReplyBit); }

// One decoded telegram. The spans point into the decoder's buffer: valid only during the
// callback that delivers it.
struct Telegram
{
    uint8_t address = 0;
    uint8_t command = 0;
    std::span<const uint8_t> data;  // the bytes after CMD, without STATUS
    bool has_status = false;        // replies carry a STATUS byte, requests do not
    uint8_t status = 0;
    std::span<const uint8_t> raw;   // the whole telegram, STX through CRC
};

// A whole telegram: header, CMD, DATA, optional STATUS, CRC. For a reply pass address
// kDeviceAddress and a status byte; for a request kHostAddress and no status.
std::vector<uint8_t> encode_telegram(uint8_t address, uint8_t command, std::span<const uint8_t> data,
                                     const uint8_t* status = nullptr);
inline std::vector<uint8_t> encode_request(uint8_t command, std::span<const uint8_t> data = {})
{
    return encode_telegram(kHostAddress, command, data, nullptr);
}
inline std::vector<uint8_t> encode_reply(uint8_t command, std::span<const uint8_t> data, uint8_t status)
{
    return encode_telegram(kDeviceAddress, command, data, &status);
}

inline uint16_t get_u16le(const uint8_t* p) { return static_cast<uint16_t>(p[0] | (p[1] << 8)); }
inline void put_u16le(std::vector<uint8_t>& out, uint16_t v)
{
    out.push_back(static_cast<uint8_t>(v & 0xff));
    out.push_back(static_cast<uint8_t>(v >> 8));
}

}  // namespace ugv::sick_lms2xx
