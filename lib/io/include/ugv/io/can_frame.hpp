// A classic CAN 2.0 frame, independent of the transport that carries it.
#pragma once

#include <array>
#include <cstdint>

namespace ugv::io {

struct CanFrame
{
    uint32_t id = 0;         // 11-bit, or 29-bit when extended
    bool extended = false;
    bool rtr = false;        // remote transmission request
    uint8_t dlc = 0;         // 0..8
    std::array<uint8_t, 8> data{};

    bool operator==(const CanFrame&) const = default;
};

}  // namespace ugv::io
