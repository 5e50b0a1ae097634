#include "object_dictionary.hpp"

#include <algorithm>
#include <iterator>

namespace ugv::sim::servo {

void ObjectDictionary::add(uint16_t index, uint8_t sub, uint32_t value, int size, Access access, bool mappable)
{
    entries_[key(index, sub)] = OdEntry{value, size, access, mappable};
}

std::vector<uint32_t> ObjectDictionary::default_mapping(bool transmit, int n)
{
    // A vendor's predefined set in the CiA 402 manner: statusword with the actual values out,
    // controlword with the set-point in.
    static const std::vector<uint32_t> tpdo[4] = {
        {0x60410010, 0x60640020}, {0x60410010, 0x606C0020}, {0x60640020, 0x606C0020}, {0x603F0010}};
    static const std::vector<uint32_t> rpdo[4] = {
        {0x60400010, 0x607A0020}, {0x60400010, 0x60600008}, {0x60810020}, {0x60830020, 0x60840020}};
    return transmit ? tpdo[n - 1] : rpdo[n - 1];
}

void ObjectDictionary::reset_communication(uint8_t node, const DriveShape& shape)
{
    for (auto it = entries_.begin(); it != entries_.end();)
        it = it->first >> 8 < 0x2000 ? entries_.erase(it) : std::next(it);
    add(0x1000, 0, 0x00020192, 4, Access::ro);  // device type: CiA 402 servo drive
    add(0x1001, 0, 0, 1, Access::ro);           // error register
    if (shape.heartbeat) add(0x1017, 0, 1000, 2, Access::rw);  // heartbeat producer time, ms
    add(0x1018, 0, 4, 1, Access::ro);           // identity
    add(0x1018, 1, 0x00000ABC, 4, Access::ro);  // vendor id (not a registered one)
    add(0x1018, 2, 0x00000402, 4, Access::ro);  // product code
    add(0x1018, 3, 0x00010000, 4, Access::ro);  // revision
    add(0x1018, 4, 0x00000001, 4, Access::ro);  // serial number
    const Access map_access = shape.fixed_mapping ? Access::ro : Access::rw;
    const int max = std::clamp(shape.max_mapped, 1, 8);
    for (int kind = 0; kind < 2; ++kind) {
        const bool transmit = kind == 0;
        for (int n = 1; n <= (transmit ? shape.tpdos : shape.rpdos); ++n) {
            const auto comm = static_cast<uint16_t>((transmit ? 0x1800 : 0x1400) + n - 1);
            const auto map = static_cast<uint16_t>((transmit ? 0x1A00 : 0x1600) + n - 1);
            const uint32_t cob = (transmit ? 0x180u : 0x200u) + 0x100u * static_cast<uint32_t>(n - 1) + node;
            add(comm, 0, transmit && !shape.sync_only ? 5 : 2, 1, Access::ro);
            add(comm, 1, (n == 1 ? 0u : 0x80000000u) | cob, 4, Access::rw);  // PDO1 valid at power-on
            add(comm, 2, transmit && shape.sync_only ? 1 : 0xFF, 1, Access::rw);
            if (transmit && !shape.sync_only) add(comm, 5, 0, 2, Access::rw);
            auto entries = default_mapping(transmit, n);
            if (static_cast<int>(entries.size()) > max) entries.resize(static_cast<std::size_t>(max));
            add(map, 0, static_cast<uint32_t>(entries.size()), 1, map_access);
            for (int s = 1; s <= max; ++s)
                add(map, static_cast<uint8_t>(s), s <= static_cast<int>(entries.size()) ? entries[static_cast<std::size_t>(s - 1)] : 0,
                    4, map_access);
        }
    }
}

void ObjectDictionary::reset_defaults(uint8_t node, const DriveShape& shape)
{
    entries_.clear();
    reset_communication(node, shape);
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
    for (uint16_t index : shape.removed) entries_.erase(key(index, 0));
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
