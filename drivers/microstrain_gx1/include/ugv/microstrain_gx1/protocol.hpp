// MicroStrain 3DM-GX1 wire protocol: command bytes, reply lengths, the 16-bit checksum and
// the encoding of every command (fact sheet: shared/protocols/microstrain-3dm-gx1.md).
//
// Every reply has the same shape: the command byte echoed, N big-endian 16-bit words, then a
// u16 checksum = (echo + sum of the N words) mod 65536. Only N depends on the command, so
// one parser handles all of them.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace ugv::microstrain_gx1 {

namespace cmd {
inline constexpr uint8_t raw_sensor = 0x01;
inline constexpr uint8_t stab_vectors = 0x02;
inline constexpr uint8_t inst_vectors = 0x03;
inline constexpr uint8_t inst_quaternion = 0x04;
inline constexpr uint8_t stab_quaternion = 0x05;
inline constexpr uint8_t capture_gyro_bias = 0x06;
inline constexpr uint8_t temperature = 0x07;
inline constexpr uint8_t inst_matrix = 0x0A;
inline constexpr uint8_t stab_matrix = 0x0B;
inline constexpr uint8_t stab_quaternion_vectors = 0x0C;
inline constexpr uint8_t inst_euler = 0x0D;
inline constexpr uint8_t stab_euler = 0x0E;
inline constexpr uint8_t tare = 0x0F;
inline constexpr uint8_t continuous = 0x10;
inline constexpr uint8_t remove_tare = 0x11;
inline constexpr uint8_t write_gains = 0x24;
inline constexpr uint8_t read_gains = 0x25;
inline constexpr uint8_t read_eeprom = 0x28;
inline constexpr uint8_t write_eeprom = 0x29;
inline constexpr uint8_t stab_euler_accel_rate = 0x31;
inline constexpr uint8_t firmware_version = 0xF0;
inline constexpr uint8_t serial_number = 0xF1;
}  // namespace cmd

// EEPROM addresses (decimal, as the fact sheet gives them).
namespace eeprom {
inline constexpr uint16_t gyro_gain_scale = 130;
inline constexpr uint16_t accel_gain_scale = 230;
inline constexpr uint16_t mag_gain_scale = 232;
inline constexpr std::array<uint16_t, 4> timing = {238, 240, 242, 246};
}  // namespace eeprom

// The longest reply (0x0C): echo + 14 words + checksum.
inline constexpr std::size_t max_reply_words = 14;
inline constexpr std::size_t max_reply_length = 1 + 2 * max_reply_words + 2;

// Reply length in bytes including echo and checksum; 0 for a byte that is not a command.
std::size_t reply_length(uint8_t command);
inline bool is_command(uint8_t b) { return reply_length(b) != 0; }
// Number of 16-bit words between the echo and the checksum.
inline std::size_t reply_words(uint8_t command)
{
    const std::size_t n = reply_length(command);
    return n == 0 ? 0 : (n - 3) / 2;
}
// True when the reply's last data word is the device timer (all replies but F0/F1/24).
bool reply_has_ticks(uint8_t command);

// (echo + sum of big-endian words) mod 65536 over `words` words that follow the echo.
uint16_t checksum(uint8_t echo, const uint8_t* words_be, std::size_t words);

// Host -> device command bytes.
std::vector<uint8_t> encode_simple(uint8_t command);                 // any one-byte command
std::vector<uint8_t> encode_start_continuous(uint8_t streamed_command);  // 10 00 cmd
std::vector<uint8_t> encode_stop_continuous();                        // 10 00 00
std::vector<uint8_t> encode_tare();                                   // 0F C1 C3 C5
std::vector<uint8_t> encode_remove_tare();                            // 11 C1 C3 C5
std::vector<uint8_t> encode_read_eeprom(uint16_t address);            // 28 hi lo
std::vector<uint8_t> encode_write_eeprom(uint16_t address, uint16_t value);  // 29 71 hi lo vh vl AA
// 24 + the three gain words the 0x25 reply returns (accel, mag, bias), big-endian.
std::vector<uint8_t> encode_write_gains(uint16_t accel_gain, uint16_t mag_gain, uint16_t bias_gain);

// Device -> host: builds a whole reply (echo, words, checksum). Used by the emulator and tests.
std::vector<uint8_t> encode_reply(uint8_t command, const std::vector<uint16_t>& words);

}  // namespace ugv::microstrain_gx1
