#include "ugv/canopen/pdo.hpp"

#include "ugv/canopen/ids.hpp"

namespace ugv::canopen {
namespace {
constexpr uint32_t kPdoDisabled = 0x80000000u;  // COB-ID bit 31: PDO does not exist / not valid
}

uint32_t PdoMapping::cob_id(uint8_t node) const
{
    const auto n = static_cast<std::size_t>(number - 1);
    return (transmit ? kTpdoBase[n] : kRpdoBase[n]) + node;
}

int PdoMapping::payload_bytes() const
{
    int bits = 0;
    for (const auto& o : objects) bits += o.bits;
    return bits / 8;
}

std::vector<SdoWrite> pdo_configuration(const PdoMapping& m, uint8_t node, bool write_mapping)
{
    const uint16_t comm = static_cast<uint16_t>((m.transmit ? 0x1800 : 0x1400) + (m.number - 1));
    const uint16_t map = static_cast<uint16_t>((m.transmit ? 0x1A00 : 0x1600) + (m.number - 1));
    const uint32_t cob = m.cob_id(node);
    std::vector<SdoWrite> w;
    w.push_back({{comm, 1}, cob | kPdoDisabled, 4});
    w.push_back({{comm, 2}, m.transmission_type, 1});
    if (m.transmit && m.event_timer_ms > 0) w.push_back({{comm, 5}, m.event_timer_ms, 2});
    if (write_mapping) {
        w.push_back({{map, 0}, 0, 1});
        for (std::size_t i = 0; i < m.objects.size(); ++i)
            w.push_back({{map, static_cast<uint8_t>(i + 1)}, m.objects[i].entry(), 4});
        w.push_back({{map, 0}, static_cast<uint32_t>(m.objects.size()), 1});
    }
    w.push_back({{comm, 1}, cob, 4});
    return w;
}

io::CanFrame pack_pdo(const PdoMapping& m, uint8_t node, const std::vector<uint32_t>& values)
{
    io::CanFrame f;
    f.id = m.cob_id(node);
    std::size_t pos = 0;
    for (std::size_t i = 0; i < m.objects.size() && i < values.size(); ++i) {
        const int nbytes = m.objects[i].bits / 8;
        for (int b = 0; b < nbytes && pos < 8; ++b) f.data[pos++] = static_cast<uint8_t>(values[i] >> (8 * b));
    }
    f.dlc = static_cast<uint8_t>(pos);
    return f;
}

std::optional<std::vector<uint32_t>> unpack_pdo(const PdoMapping& m, uint8_t node, const io::CanFrame& f)
{
    if (f.id != m.cob_id(node) || f.extended || f.rtr || f.dlc < m.payload_bytes()) return std::nullopt;
    std::vector<uint32_t> values;
    values.reserve(m.objects.size());
    std::size_t pos = 0;
    for (const auto& o : m.objects) {
        uint32_t v = 0;
        for (int b = 0; b < o.bits / 8; ++b) v |= static_cast<uint32_t>(f.data[pos++]) << (8 * b);
        values.push_back(v);
    }
    return values;
}

}  // namespace ugv::canopen
