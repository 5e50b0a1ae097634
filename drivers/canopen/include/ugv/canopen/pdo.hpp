// PDO mapping (CiA 301): the SDO writes that configure one TPDO or RPDO, and packing and
// unpacking of the mapped values in a PDO frame.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "ugv/canopen/sdo.hpp"
#include "ugv/io/can_frame.hpp"

namespace ugv::canopen {

struct MappedObject
{
    uint16_t index = 0;
    uint8_t subindex = 0;
    uint8_t bits = 0;  // 8, 16 or 32
    // The mapping entry as written to 0x1600/0x1A00 sub n: index << 16 | sub << 8 | bits.
    uint32_t entry() const { return (uint32_t{index} << 16) | (uint32_t{subindex} << 8) | bits; }
};

// Transmission types: 1..240 = after every n-th SYNC; 0xFE/0xFF = on event (timer/change).
inline constexpr uint8_t kTransmissionEvent = 0xFF;

struct PdoMapping
{
    bool transmit = true;          // TPDO (drive -> host) or RPDO (host -> drive)
    int number = 1;                // 1..4
    uint8_t transmission_type = kTransmissionEvent;
    uint16_t event_timer_ms = 0;   // TPDO sub-index 5: send at least this often (0 = off)
    std::vector<MappedObject> objects;

    uint32_t cob_id(uint8_t node) const;
    int payload_bytes() const;
};

struct SdoWrite
{
    SdoAddress at;
    uint32_t value = 0;
    int size = 0;
    bool operator==(const SdoWrite&) const = default;
};

// The CiA 301 sequence: disable the PDO (COB-ID bit 31), set the transmission type (and
// event timer), clear the mapping count, write the entries, set the count, enable.
// write_mapping false: the drive's own (fixed) mapping stays; only the communication part.
std::vector<SdoWrite> pdo_configuration(const PdoMapping& mapping, uint8_t node, bool write_mapping = true);

// Packs values (one per mapped object, little-endian, in order) into a PDO frame.
io::CanFrame pack_pdo(const PdoMapping& mapping, uint8_t node, const std::vector<uint32_t>& values);
// Unpacks a PDO frame of this mapping; nullopt when the id or length does not match.
std::optional<std::vector<uint32_t>> unpack_pdo(const PdoMapping& mapping, uint8_t node, const io::CanFrame& frame);

}  // namespace ugv::canopen
