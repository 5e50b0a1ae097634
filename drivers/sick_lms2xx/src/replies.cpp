#include "ugv/sick_lms2xx/replies.hpp"

#include <algorithm>

namespace ugv::sick_lms2xx {

static std::string printable(std::span<const uint8_t> bytes)
{
    std::string s;
    for (const uint8_t b : bytes)
        if (b >= 0x20 && b < 0x7f) s.push_back(static_cast<char>(b));
    return s;
}

std::optional<uint8_t> decode_mode_reply(const Telegram& t)
{
    if (t.command != reply_command(cmd::switch_mode) || t.data.empty()) return std::nullopt;
    return t.data[0];
}

std::optional<VariantReply> decode_variant_reply(const Telegram& t)
{
    if (t.command != reply_command(cmd::variant) || t.data.empty()) return std::nullopt;
    VariantReply r;
    r.accepted = t.data[0] == 0x01;
    if (t.data.size() >= 5) {
        r.angle_deg = get_u16le(t.data.data() + 1);
        r.resolution_cdeg = get_u16le(t.data.data() + 3);
    }
    return r;
}

std::optional<DeviceConfig> decode_config_reply(const Telegram& t)
{
    if (t.command != reply_command(cmd::read_config) || t.data.size() < kConfigMinBytes) return std::nullopt;
    return DeviceConfig{std::vector<uint8_t>(t.data.begin(), t.data.end())};
}

std::optional<bool> decode_write_config_reply(const Telegram& t)
{
    if (t.command != reply_command(cmd::write_config) || t.data.empty()) return std::nullopt;
    return t.data[0] == 0x01;
}

std::optional<std::string> decode_type_reply(const Telegram& t)
{
    if (t.command != reply_command(cmd::type)) return std::nullopt;
    return printable(t.data);
}

std::optional<StatusReply> decode_status_reply(const Telegram& t)
{
    if (t.command != reply_command(cmd::status) || t.data.empty()) return std::nullopt;
    StatusReply r;
    r.block.assign(t.data.begin(), t.data.end());
    r.version = printable(t.data.first(std::min<std::size_t>(7, t.data.size())));
    return r;
}

bool is_reset_reply(const Telegram& t) { return t.command == cmd::reset_reply; }

}  // namespace ugv::sick_lms2xx
