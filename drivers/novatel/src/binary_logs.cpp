// OEM4 binary logs: the little-endian header (offsets from the fact sheet); the body is
// read by the layout the log table names for the message id.
#include "body_fields.hpp"
#include "body_layout.hpp"
#include "ugv/novatel/log_decoding.hpp"

namespace ugv::novatel {
namespace {

constexpr std::size_t kShortHeader = 12;
constexpr std::size_t kCrcBytes = 4;

LogHeader long_header(const uint8_t* f)
{
    LogHeader h;
    h.kind = FrameKind::binary;
    h.id = get<uint16_t>(f + 4);
    h.response = (f[6] & 0x80U) != 0;
    h.sequence = get<uint16_t>(f + 10);
    h.idle_percent = f[12] / 2.0;
    h.time_status = f[13];
    h.week = get<uint16_t>(f + 14);
    h.ms = get<uint32_t>(f + 16);
    h.receiver_status = get<uint32_t>(f + 20);
    h.software_build = get<uint16_t>(f + 26);
    return h;
}

LogHeader short_header(const uint8_t* f)
{
    LogHeader h;
    h.kind = FrameKind::binary_short;
    h.id = get<uint16_t>(f + 4);
    h.week = get<uint16_t>(f + 6);
    h.ms = get<uint32_t>(f + 8);
    return h;
}

}  // namespace

DecodeStatus decode_binary(const uint8_t* f, std::size_t size, FrameKind kind, Message& out, uint16_t& id)
{
    const bool is_short = kind == FrameKind::binary_short;
    const std::size_t header_len = is_short ? kShortHeader : f[3];
    if (size < header_len + kCrcBytes) {
        return DecodeStatus::malformed;
    }
    const LogHeader h = is_short ? short_header(f) : long_header(f);
    id = h.id;
    if (h.response) {
        return DecodeStatus::response;
    }
    const uint8_t* body = f + header_len;
    const std::size_t body_len = size - header_len - kCrcBytes;
    // The table says which body this id has; an id it lacks is a log we skip.
    const LogInfo* log = find_log(h.id);
    if (log == nullptr) {
        return DecodeStatus::unknown;
    }
    const BodyLayout& layout = *log->layout;
    if (body_len < layout.binary_size) {
        return DecodeStatus::malformed;
    }
    out = layout.from_binary(h, body);
    return layout.plausible(out) ? DecodeStatus::decoded : DecodeStatus::malformed;
}

}  // namespace ugv::novatel
