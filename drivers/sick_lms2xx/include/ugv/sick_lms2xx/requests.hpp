// Every request the session sends, as complete telegrams (header and CRC included).
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace ugv::sick_lms2xx {

// The line rates the LMS 2xx supports, in the order a host probes them.
inline constexpr int kSupportedBauds[] = {9600, 19200, 38400, 500000};

// The `20 xx` mode byte that switches the device to baud; nullopt for an unsupported rate.
std::optional<uint8_t> baud_mode_byte(int baud);

inline constexpr uint8_t kModeInstallation = 0x00;
inline constexpr uint8_t kModeStreamAll = 0x24;    // continuous output of all values
inline constexpr uint8_t kModeRequest = 0x25;      // stop streaming (request mode)
inline constexpr uint8_t kModeBaud38400 = 0x40;
inline constexpr uint8_t kModeBaud19200 = 0x41;
inline constexpr uint8_t kModeBaud9600 = 0x42;
inline constexpr uint8_t kModeBaud500000 = 0x48;
inline constexpr const char* kDefaultPassword = "SICK_LMS";

std::vector<uint8_t> request_baud(int baud);  // throws std::invalid_argument on an unsupported rate
std::vector<uint8_t> request_installation_mode(const std::string& password = kDefaultPassword);
std::vector<uint8_t> request_start_streaming();
std::vector<uint8_t> request_stop_streaming();
std::vector<uint8_t> request_type();
std::vector<uint8_t> request_status();
// angle_deg 100 or 180; resolution_cdeg 25, 50 or 100 (hundredths of a degree).
std::vector<uint8_t> request_variant(int angle_deg, int resolution_cdeg);
std::vector<uint8_t> request_read_config();
// block: the configuration as read with 0x74 (the bytes after the reply's CMD), modified.
std::vector<uint8_t> request_write_config(std::span<const uint8_t> block);
std::vector<uint8_t> request_reset();

}  // namespace ugv::sick_lms2xx
