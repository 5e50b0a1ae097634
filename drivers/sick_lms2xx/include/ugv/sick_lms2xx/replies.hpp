// Decoding of the device's replies to the session's requests. Each decoder returns nullopt
// for a telegram that is not the reply it decodes or is too short to be one.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "ugv/sick_lms2xx/telegram.hpp"

namespace ugv::sick_lms2xx {

// 0xA0, the answer to every `20 xx` mode switch: 0x00 success, 0x01 wrong password,
// 0x02 refused because of a device fault; other codes are passed through.
inline constexpr uint8_t kModeOk = 0x00;
inline constexpr uint8_t kModeBadPassword = 0x01;
inline constexpr uint8_t kModeFault = 0x02;
std::optional<uint8_t> decode_mode_reply(const Telegram& t);

// 0xBB, the answer to a variant request.
struct VariantReply
{
    bool accepted = false;
    int angle_deg = 0;        // as echoed (0 when the reply is too short to carry it)
    int resolution_cdeg = 0;  // 0.01 deg
};
std::optional<VariantReply> decode_variant_reply(const Telegram& t);

// The configuration block of 0x74/0x77 (the bytes after CMD). Its length varies with the
// firmware (32-42 bytes), so it is kept whole and written back as read, changing only the
// bytes the session owns.
inline constexpr uint8_t kAvailabilityScanIndex = 0x02;  // add the real-time scan index
inline constexpr uint8_t kMeasuringMode8m80m = 0x00;     // 13-bit range + fields A/B/dazzle
inline constexpr uint8_t kMeasuringMode32m = 0x06;
inline constexpr uint8_t kConfigUnitsCm = 0x00;
inline constexpr uint8_t kConfigUnitsMm = 0x01;
inline constexpr std::size_t kConfigMinBytes = 7;

struct DeviceConfig
{
    std::vector<uint8_t> block;
    // Offsets in block (byte 0 = the first byte after CMD).
    static constexpr std::size_t availability_at = 4;
    static constexpr std::size_t measuring_mode_at = 5;
    static constexpr std::size_t units_at = 6;

    uint8_t availability() const { return block[availability_at]; }
    uint8_t measuring_mode() const { return block[measuring_mode_at]; }
    uint8_t units() const { return block[units_at]; }
    void set_availability(uint8_t v) { block[availability_at] = v; }
    void set_measuring_mode(uint8_t v) { block[measuring_mode_at] = v; }
    void set_units(uint8_t v) { block[units_at] = v; }
};
std::optional<DeviceConfig> decode_config_reply(const Telegram& t);        // 0xF4
// 0xF7: true = configuration accepted (byte 1 = 0x01).
std::optional<bool> decode_write_config_reply(const Telegram& t);
// 0xBA: the type string, e.g. "LMS200;30106" (non-printable bytes dropped).
std::optional<std::string> decode_type_reply(const Telegram& t);
// 0xB1: the status block; only the software version text (its first 7 bytes) is interpreted.
struct StatusReply
{
    std::string version;
    std::vector<uint8_t> block;
};
std::optional<StatusReply> decode_status_reply(const Telegram& t);
// 0x91: the device accepted the reset.
bool is_reset_reply(const Telegram& t);

}  // namespace ugv::sick_lms2xx
