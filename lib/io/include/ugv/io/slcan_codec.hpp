// The Lawicel / slcan ASCII protocol (CANable, USBtin class adapters), without I/O.
//   "tiiildd..\r" standard frame, "Tiiiiiiiildd..\r" extended, "riiil\r"/"Riiiiiiiil\r" RTR;
//   "S0".."S8\r" bitrate, "O\r" open, "C\r" close; replies "\r" = OK, "\a" (BEL) = error;
//   "z\r"/"Z\r" acknowledge a transmitted frame on some adapters.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "ugv/io/can_frame.hpp"

namespace ugv::io::slcan {

std::string encode_frame(const CanFrame& frame);
// "S<n>\r" for one of the standard bitrates; nullopt for a rate slcan cannot set.
std::optional<std::string> encode_bitrate(int bitrate);
inline std::string open_command() { return "O\r"; }
inline std::string close_command() { return "C\r"; }

// What one line (or BEL) from the adapter meant.
struct Event
{
    enum class Kind { frame, ok, error, tx_ack, malformed };
    Kind kind = Kind::malformed;
    CanFrame frame;
    std::string text;  // the raw line, for malformed
};

// Splits the byte stream into lines and decodes them. Feed any chunks; returns the events
// completed by this chunk. Lines longer than any valid one are discarded (counted).
class Decoder
{
public:
    std::vector<Event> feed(const uint8_t* data, std::size_t n);
    uint64_t malformed() const { return malformed_; }

private:
    std::string line_;
    uint64_t malformed_ = 0;
};

// Decodes one line without its '\r'. Returns kind malformed for anything invalid.
Event decode_line(std::string_view line);

}  // namespace ugv::io::slcan
