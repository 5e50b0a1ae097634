// NovAtel ASCII logs: "#NAMEA,port,seq,idle,timestatus,week,seconds,rxstatus,reserved,sw;body"
// and short "%NAMEA,week,seconds;body". Enums are printed as names. The header is read
// here; the body by the layout the log table names for the log.
#include <cmath>

#include "body_layout.hpp"
#include "ugv/novatel/checksum.hpp"
#include "ugv/novatel/enums.hpp"
#include "ugv/novatel/log_decoding.hpp"
#include "ugv/novatel/text_fields.hpp"

namespace ugv::novatel {
namespace {

bool parse_seconds_ms(std::string_view field, uint32_t& ms)
{
    double seconds = 0;
    if (!parse_double(field, seconds) || seconds < 0 || seconds > 604800.0) {
        return false;
    }
    ms = static_cast<uint32_t>(std::llround(seconds * 1000.0));
    return true;
}

bool parse_hex_field(std::string_view field, uint32_t& value)
{
    return !field.empty() && field.size() <= 8 &&
           parse_hex(reinterpret_cast<const uint8_t*>(field.data()), field.size(), value);
}

bool parse_header(std::string_view text, FrameKind kind, LogHeader& h)
{
    FieldReader r(text);
    std::string_view f;
    h.kind = kind;
    r.next(f);  // the name, already read by the caller
    if (kind == FrameKind::ascii_short) {
        uint32_t week = 0;
        if (!r.next(f) || !parse_uint(f, week) || !r.next(f) || !parse_seconds_ms(f, h.ms)) {
            return false;
        }
        h.week = week;
        return true;
    }
    std::string_view port, seq, idle, status, week, seconds, rx, reserved, sw;
    if (!r.next(port) || !r.next(seq) || !r.next(idle) || !r.next(status) || !r.next(week) ||
        !r.next(seconds) || !r.next(rx) || !r.next(reserved) || !r.next(sw)) {
        return false;
    }
    uint32_t sequence = 0, build = 0;
    if (!parse_uint(seq, sequence) || !parse_uint(week, h.week) || !parse_seconds_ms(seconds, h.ms) ||
        !parse_hex_field(rx, h.receiver_status)) {
        return false;
    }
    h.sequence = static_cast<uint16_t>(sequence);
    parse_double(idle, h.idle_percent);
    if (parse_uint(sw, build)) {
        h.software_build = static_cast<uint16_t>(build);
    }
    h.time_status = time_status_from_name(status);
    return true;
}

}  // namespace

DecodeStatus decode_ascii(const uint8_t* frame, std::size_t size, FrameKind kind, Message& out,
                          std::string_view& name)
{
    // Between the '#'/'%' and the "*xxxxxxxx" checksum.
    if (size < 10) {
        return DecodeStatus::malformed;
    }
    const std::string_view text(reinterpret_cast<const char*>(frame) + 1, size - 10);
    const auto semicolon = text.find(';');
    name = text.substr(0, text.find(','));
    if (semicolon == std::string_view::npos || name.empty() || name.size() > semicolon) {
        return DecodeStatus::malformed;
    }
    // The last letter is the format (A = ASCII); the table knows the name without it.
    const LogInfo* log = find_log(name.substr(0, name.size() - 1));
    if (name.back() != 'A' || log == nullptr) {
        return DecodeStatus::unknown;
    }
    LogHeader h;
    if (!parse_header(text.substr(0, semicolon), kind, h)) {
        return DecodeStatus::malformed;
    }
    h.id = log->id;
    const BodyLayout& layout = *log->layout;
    if (!layout.from_ascii(h, text.substr(semicolon + 1), out) || !layout.plausible(out)) {
        return DecodeStatus::malformed;
    }
    return DecodeStatus::decoded;
}

}  // namespace ugv::novatel
