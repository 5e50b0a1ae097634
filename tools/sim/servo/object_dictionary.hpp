// The emulated drive's object dictionary: the CiA 301 communication objects and the CiA 402
// objects a profile-position drive has, with access rights and PDO mappability, so the SDO
// server can answer as a real drive does (including its aborts).
#pragma once

#include <cstdint>
#include <map>
#include <optional>

namespace ugv::sim::servo {

enum class Access { ro, rw, wo };

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
    void reset_defaults(uint8_t node);
    // Restores only the communication area 0x1000-0x1FFF (NMT reset communication).
    void reset_communication(uint8_t node);

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
