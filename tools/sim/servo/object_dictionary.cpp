#include "object_dictionary.hpp"

namespace ugv::sim::servo {

void ObjectDictionary::add(uint16_t index, uint8_t sub, uint32_t value, int size, Access access, bool mappable)
{
    entries_[key(index, sub)] = OdEntry{value, size, access, mappable};
}

void ObjectDictionary::reset_communication(uint8_t node)
{
    add(0x1000, 0, 0x00020192, 4, Access::ro);  // device type: CiA 402 servo drive
    add(0x1001, 0, 0, 1, Access::ro);           // error register
    add(0x1017, 0, 1000, 2, Access::rw);        // heartbeat producer time, ms
    // Default PDO set (CiA 402 style): TPDO1 statusword, RPDO1 controlword; the others empty.
    for (uint16_t n = 0; n < 4; ++n) {
        add(static_cast<uint16_t>(0x1400 + n), 0, 2, 1, Access::ro);
        add(static_cast<uint16_t>(0x1400 + n), 1, (n == 0 ? 0u : 0x80000000u) | (0x200u + 0x100u * n + node), 4, Access::rw);
        add(static_cast<uint16_t>(0x1400 + n), 2, 0xFF, 1, Access::rw);
        add(static_cast<uint16_t>(0x1800 + n), 0, 5, 1, Access::ro);
        add(static_cast<uint16_t>(0x1800 + n), 1, (n == 0 ? 0u : 0x80000000u) | (0x180u + 0x100u * n + node), 4, Access::rw);
        add(static_cast<uint16_t>(0x1800 + n), 2, 0xFF, 1, Access::rw);
        add(static_cast<uint16_t>(0x1800 + n), 5, 0, 2, Access::rw);
        add(static_cast<uint16_t>(0x1600 + n), 0, n == 0 ? 1u : 0u, 1, Access::rw);
        add(static_cast<uint16_t>(0x1A00 + n), 0, n == 0 ? 1u : 0u, 1, Access::rw);
        for (uint8_t s = 1; s <= 8; ++s) {
            add(static_cast<uint16_t>(0x1600 + n), s, 0, 4, Access::rw);
            add(static_cast<uint16_t>(0x1A00 + n), s, 0, 4, Access::rw);
        }
    }
    set(0x1600, 1, 0x60400010);
    set(0x1A00, 1, 0x60410010);
}

void ObjectDictionary::reset_defaults(uint8_t node)
{
    entries_.clear();
    reset_communication(node);
    add(0x603F, 0, 0, 2, Access::ro, true);           // error code
    add(0x6040, 0, 0, 2, Access::rw, true);           // controlword
    add(0x6041, 0, 0, 2, Access::ro, true);           // statusword
    add(0x6060, 0, 0, 1, Access::rw, true);           // modes of operation
    add(0x6061, 0, 0, 1, Access::ro, true);           // modes of operation display
    add(0x6064, 0, 0, 4, Access::ro, true);           // position actual, counts
    add(0x606C, 0, 0, 4, Access::ro, true);           // velocity actual, counts/s
    add(0x607A, 0, 0, 4, Access::rw, true);           // target position, counts
    add(0x6081, 0, 10000, 4, Access::rw, true);       // profile velocity, counts/s
    add(0x6083, 0, 100000, 4, Access::rw, true);      // profile acceleration, counts/s^2
    add(0x6084, 0, 100000, 4, Access::rw, true);      // profile deceleration, counts/s^2
    add(0x6502, 0, 0x00000005, 4, Access::ro);        // supported modes: pp and pv
}

OdEntry* ObjectDictionary::find(uint16_t index, uint8_t sub)
{
    const auto it = entries_.find(key(index, sub));
    return it == entries_.end() ? nullptr : &it->second;
}

const OdEntry* ObjectDictionary::find(uint16_t index, uint8_t sub) const
{
    const auto it = entries_.find(key(index, sub));
    return it == entries_.end() ? nullptr : &it->second;
}

uint32_t ObjectDictionary::get(uint16_t index, uint8_t sub) const
{
    const OdEntry* e = find(index, sub);
    return e ? e->value : 0;
}

void ObjectDictionary::set(uint16_t index, uint8_t sub, uint32_t value)
{
    if (OdEntry* e = find(index, sub)) e->value = value;
}

}  // namespace ugv::sim::servo
