// CANopen (CiA 301) identifiers: the predefined connection set for 11-bit COB-IDs.
#pragma once

#include <cstdint>

namespace ugv::canopen {

// Function codes (COB-ID = base + node id, node id 1..127).
inline constexpr uint32_t kNmtId = 0x000;
inline constexpr uint32_t kSyncId = 0x080;
inline constexpr uint32_t kEmcyBase = 0x080;
inline constexpr uint32_t kTpdoBase[4] = {0x180, 0x280, 0x380, 0x480};
inline constexpr uint32_t kRpdoBase[4] = {0x200, 0x300, 0x400, 0x500};
inline constexpr uint32_t kSdoResponseBase = 0x580;  // server -> client
inline constexpr uint32_t kSdoRequestBase = 0x600;   // client -> server
inline constexpr uint32_t kHeartbeatBase = 0x700;

inline constexpr bool valid_node_id(int node) { return node >= 1 && node <= 127; }

// The node id a COB-ID belongs to, and its function code (COB-ID without the node bits).
inline constexpr uint8_t node_of(uint32_t cob_id) { return static_cast<uint8_t>(cob_id & 0x7F); }
inline constexpr uint32_t function_of(uint32_t cob_id) { return cob_id & 0x780; }

}  // namespace ugv::canopen
