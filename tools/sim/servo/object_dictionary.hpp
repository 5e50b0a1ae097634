// The emulated drive's object dictionary: the CiA 301 communication objects and the CiA 402
// objects a profile-position drive has, with access rights and PDO mappability, so the SDO
// server can answer as a real drive does (including its aborts).
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

namespace ugv::sim::servo {

enum class Access { ro, rw, wo };

// The PDO resources and communication objects of a drive (drives differ: CiA 301 allows one
// to 512 PDOs of each kind; we model up to 4).
struct DriveShape
{
    int tpdos = 4;               // TPDOs present (1..4); the others answer 0x06020000
    int rpdos = 4;               // RPDOs present (1..4)
    bool fixed_mapping = false;  // mapping objects read-only: writes abort 0x06010002
    int max_mapped = 8;          // mapping sub-indices per PDO (1..8): beyond, 0x06090011 / 0x06040042
    bool heartbeat = true;       // 0x1017 exists (else only the boot-up message is sent)
    bool sync_only = false;      // TPDOs have no event timer (sub 5 absent, type 0xFE/0xFF refused)
    std::vector<uint16_t> removed;  // CiA 402 objects this drive does not have
};

struct OdEntry
{
    uint32_t value = 0;
    int size = 4;  // bytes
    Access access = Access::rw;
    bool mappable = false;
};

class ObjectDictionary
{
public:
    // Fills in the drive's defaults (as after power-on).
    void reset_defaults(uint8_t node, const DriveShape& shape);
    // Restores only the communication area 0x1000-0x1FFF (NMT reset communication).
    void reset_communication(uint8_t node, const DriveShape& shape);
    // The default mapping of TPDO/RPDO n (1..4), before the shape's object limit.
    static std::vector<uint32_t> default_mapping(bool transmit, int n);

    OdEntry* find(uint16_t index, uint8_t sub);
    const OdEntry* find(uint16_t index, uint8_t sub) const;
    uint32_t get(uint16_t index, uint8_t sub) const;
    // Sets a value without access checks (the drive's own updates, e.g. the statusword).
    void set(uint16_t index, uint8_t sub, uint32_t value);

private:
    void add(uint16_t index, uint8_t sub, uint32_t value, int size, Access access, bool mappable = false);
    static uint32_t key(uint16_t index, uint8_t sub) { return (uint32_t{index} << 8) | sub; }
    std::map<uint32_t, OdEntry> entries_;
};

}  // namespace ugv::sim::servo
