// Receiver-side encoding: builds the frames a receiver sends (binary logs, ASCII logs, NMEA
// sentences) and the commands a host sends. Used by the emulator and by tests; the
// session uses the command builders.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ugv/novatel/log_table.hpp"
#include "ugv/novatel/messages.hpp"

namespace ugv::novatel {

// A long-header binary frame: header (28 bytes) + body + CRC-32.
std::vector<uint8_t> encode_binary(const LogHeader& header, const std::vector<uint8_t>& body);
// The binary body of any log in the table; empty when m is not the struct of its layout.
std::vector<uint8_t> encode_body(const LogInfo& log, const Message& m);
std::vector<uint8_t> encode_position_body(const Position& p);   // 72 bytes
std::vector<uint8_t> encode_velocity_body(const Velocity& v);   // 44 bytes

// "#NAME,port,seq,idle,timestatus,week,seconds,rxstatus,reserved,sw;fields*crc\r\n".
std::string encode_ascii(std::string_view name, const LogHeader& header, std::string_view fields);
// The ASCII fields of any log in the table; empty when m is not the struct of its layout.
std::string encode_fields(const LogInfo& log, const Message& m);
std::string position_fields(const Position& p);   // the BESTPOSA body
std::string velocity_fields(const Velocity& v);   // the BESTVELA body

// "$<body>*hh\r\n" for a body like "GPGGA,...".
std::string encode_nmea(std::string_view body);
std::string gga_body(const Gga& g);
std::string rmc_body(const Rmc& r);
std::string gst_body(const Gst& g);

// Host commands (each ends with CR LF).
std::string unlogall_command();
std::string log_command(std::string_view message, double period_s);  // LOG <message> ONTIME <period>
std::string com_command(int baud);                                     // COM <baud> (this port)

// A command as the receiver reads it (case-insensitive keywords, optional port argument).
struct Command
{
    enum class Type { unlogall, log, com, unknown } type = Type::unknown;
    std::string message;       // LOG: upper case, e.g. "BESTPOSB"
    std::string trigger;       // LOG: "ONTIME", "ONCE", ... (upper case)
    double period_s = 0;       // LOG ONTIME period
    int baud = 0;              // COM
};
Command parse_command(std::string_view line);

}  // namespace ugv::novatel
