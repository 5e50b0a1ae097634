#include "ugv/microstrain_gx1/protocol.hpp"

namespace ugv::microstrain_gx1 {

std::size_t reply_length(uint8_t command)
{
    switch (command) {
    case cmd::raw_sensor:
    case cmd::stab_vectors:
    case cmd::inst_vectors:
    case cmd::inst_matrix:
    case cmd::stab_matrix:
    case cmd::stab_euler_accel_rate: return 23;
    case cmd::inst_quaternion:
    case cmd::stab_quaternion: return 13;
    case cmd::capture_gyro_bias:
    case cmd::tare:
    case cmd::remove_tare:
    case cmd::write_gains:
    case cmd::firmware_version:
    case cmd::serial_number: return 5;
    case cmd::temperature:
    case cmd::continuous:
    case cmd::read_eeprom:
    case cmd::write_eeprom: return 7;
    case cmd::stab_quaternion_vectors: return 31;
    case cmd::inst_euler:
    case cmd::stab_euler: return 11;
    case cmd::read_gains: return 11;
    default: return 0;
    }
}

bool reply_has_ticks(uint8_t command)
{
    return is_command(command) && command != cmd::firmware_version && command != cmd::serial_number;
}

uint16_t checksum(uint8_t echo, const uint8_t* words_be, std::size_t words)
{
    uint32_t sum = echo;
    for (std::size_t i = 0; i < words; ++i)
        sum += static_cast<uint32_t>(words_be[2 * i] << 8 | words_be[2 * i + 1]);
    return static_cast<uint16_t>(sum & 0xFFFFu);
}

static void put_u16(std::vector<uint8_t>& out, uint16_t v)
{
    out.push_back(static_cast<uint8_t>(v >> 8));
    out.push_back(static_cast<uint8_t>(v & 0xFF));
}

std::vector<uint8_t> encode_simple(uint8_t command) { return {command}; }

std::vector<uint8_t> encode_start_continuous(uint8_t streamed_command)
{
    return {cmd::continuous, 0x00, streamed_command};
}

std::vector<uint8_t> encode_stop_continuous() { return {cmd::continuous, 0x00, 0x00}; }

// The tare commands carry a fixed confirmation sequence so a stray byte cannot tare the unit.
std::vector<uint8_t> encode_tare() { return {cmd::tare, 0xC1, 0xC3, 0xC5}; }
std::vector<uint8_t> encode_remove_tare() { return {cmd::remove_tare, 0xC1, 0xC3, 0xC5}; }

std::vector<uint8_t> encode_read_eeprom(uint16_t address)
{
    std::vector<uint8_t> out{cmd::read_eeprom};
    put_u16(out, address);
    return out;
}

std::vector<uint8_t> encode_write_eeprom(uint16_t address, uint16_t value)
{
    std::vector<uint8_t> out{cmd::write_eeprom, 0x71};
    put_u16(out, address);
    put_u16(out, value);
    out.push_back(0xAA);
    return out;
}

std::vector<uint8_t> encode_write_gains(uint16_t accel_gain, uint16_t mag_gain, uint16_t bias_gain)
{
    std::vector<uint8_t> out{cmd::write_gains};
    put_u16(out, accel_gain);
    put_u16(out, mag_gain);
    put_u16(out, bias_gain);
    return out;
}

std::vector<uint8_t> encode_reply(uint8_t command, const std::vector<uint16_t>& words)
{
    std::vector<uint8_t> out;
    out.reserve(3 + 2 * words.size());
    out.push_back(command);
    for (uint16_t w : words) put_u16(out, w);
    put_u16(out, checksum(command, out.data() + 1, words.size()));
    return out;
}

}  // namespace ugv::microstrain_gx1
