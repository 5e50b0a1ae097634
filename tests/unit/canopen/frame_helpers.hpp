// Building CAN frames from the "ID#HEX" notation of the fact sheet and candump.
#pragma once

#include <cstdlib>
#include <string>

#include "ugv/io/can_frame.hpp"

namespace canopen_test {

inline ugv::io::CanFrame frame(const std::string& text)
{
    ugv::io::CanFrame f;
    const auto hash = text.find('#');
    f.id = static_cast<uint32_t>(std::strtoul(text.substr(0, hash).c_str(), nullptr, 16));
    const std::string hex = text.substr(hash + 1);
    f.dlc = static_cast<uint8_t>(hex.size() / 2);
    for (std::size_t i = 0; i < f.dlc; ++i)
        f.data[i] = static_cast<uint8_t>(std::strtoul(hex.substr(2 * i, 2).c_str(), nullptr, 16));
    return f;
}

inline std::string text(const ugv::io::CanFrame& f)
{
    static const char* digits = "0123456789ABCDEF";
    std::string s;
    for (int shift = 8; shift >= 0; shift -= 4) s += digits[(f.id >> shift) & 0xF];
    s += '#';
    for (std::size_t i = 0; i < f.dlc; ++i) {
        s += digits[f.data[i] >> 4];
        s += digits[f.data[i] & 0xF];
    }
    return s;
}

}  // namespace canopen_test
