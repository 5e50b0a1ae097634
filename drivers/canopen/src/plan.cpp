#include "ugv/canopen/plan.hpp"

#include <algorithm>
#include <cstdio>

#include "ugv/canopen/cia402.hpp"
#include "ugv/canopen/sdo.hpp"

namespace ugv::canopen {
namespace {

namespace c4 = cia402;

std::string hex16(uint32_t v)
{
    char b[16];
    std::snprintf(b, sizeof b, "0x%04X", v);
    return b;
}

std::string hex32(uint32_t v)
{
    char b[16];
    std::snprintf(b, sizeof b, "0x%08X", v);
    return b;
}

uint8_t bits_of(uint16_t index)
{
    switch (index) {
    case c4::kControlword:
    case c4::kStatusword:
    case c4::kErrorCode: return 16;
    case c4::kModesOfOperation:
    case c4::kModesDisplay: return 8;
    default: return 32;
    }
}

MappedObject object(uint16_t index) { return {index, 0, bits_of(index)}; }

// Objects whose value the session knows when it sends an RPDO (a fixed RPDO carrying
// anything else cannot be sent without writing a value we do not know).
bool known_rpdo_object(uint16_t index)
{
    return index == c4::kControlword || index == c4::kTargetPosition || index == c4::kProfileVelocity ||
           index == c4::kModesOfOperation || index == c4::kProfileAcceleration || index == c4::kProfileDeceleration;
}

std::string pdo_name(const PdoResource& r) { return (r.transmit ? "TPDO" : "RPDO") + std::to_string(r.number); }

std::string list_objects(const std::vector<MappedObject>& objs)
{
    std::string s;
    for (const auto& o : objs) s += (s.empty() ? "" : " + ") + std::string(object_name(o.index));
    return s.empty() ? "nothing" : s;
}

// Picks PDOs for wanted objects. A remappable PDO takes the objects it may hold; a fixed
// one is taken when its own mapping holds them (and, for RPDOs, only objects we can fill).
class Picker
{
public:
    Picker(const std::vector<PdoResource>& pdos, const DriveCapabilities& caps) : caps_(caps)
    {
        for (const auto& p : pdos)
            if (p.present) free_.push_back(&p);
    }

    bool mappable(const PdoResource& p, uint16_t index) const
    {
        return p.remappable && caps_.unmappable.count(object(index).entry()) == 0 && caps_.has(index);
    }

    // A remappable PDO for these objects (all of them), preferring the lowest number.
    std::optional<Plan::Pdo> remap(const std::vector<uint16_t>& wanted)
    {
        int bits = 0;
        for (uint16_t i : wanted) bits += bits_of(i);
        if (bits > 64) return std::nullopt;
        for (auto it = free_.begin(); it != free_.end(); ++it) {
            const PdoResource& p = **it;
            if (static_cast<int>(wanted.size()) > p.max_objects) continue;
            if (!std::all_of(wanted.begin(), wanted.end(), [&](uint16_t i) { return mappable(p, i); })) continue;
            Plan::Pdo out;
            out.mapping.transmit = p.transmit;
            out.mapping.number = p.number;
            for (uint16_t i : wanted) out.mapping.objects.push_back(object(i));
            free_.erase(it);
            return out;
        }
        return std::nullopt;
    }

    // A fixed PDO whose own mapping holds every wanted object.
    std::optional<Plan::Pdo> as_is(const std::vector<uint16_t>& wanted)
    {
        for (auto it = free_.begin(); it != free_.end(); ++it) {
            const PdoResource& p = **it;
            if (p.remappable || p.default_mapping.empty()) continue;
            if (!std::all_of(wanted.begin(), wanted.end(), [&](uint16_t i) { return p.contains(i); })) continue;
            if (!p.transmit && !std::all_of(p.default_mapping.begin(), p.default_mapping.end(),
                                            [](const MappedObject& o) { return known_rpdo_object(o.index); }))
                continue;
            Plan::Pdo out;
            out.mapping.transmit = p.transmit;
            out.mapping.number = p.number;
            out.mapping.objects = p.default_mapping;
            out.write_mapping = false;
            free_.erase(it);
            return out;
        }
        return std::nullopt;
    }

    std::optional<Plan::Pdo> any(const std::vector<uint16_t>& wanted)
    {
        if (auto p = remap(wanted)) return p;
        return as_is(wanted);
    }

private:
    const DriveCapabilities& caps_;
    std::vector<const PdoResource*> free_;
};

bool carries(const std::vector<Plan::Pdo>& pdos, uint16_t index)
{
    for (const auto& p : pdos)
        for (const auto& o : p.mapping.objects)
            if (o.index == index) return true;
    return false;
}

}  // namespace

bool PdoResource::contains(uint16_t index) const
{
    return std::any_of(default_mapping.begin(), default_mapping.end(), [&](const MappedObject& o) { return o.index == index; });
}

const char* object_name(uint16_t index)
{
    switch (index) {
    case c4::kControlword: return "controlword 0x6040";
    case c4::kStatusword: return "statusword 0x6041";
    case c4::kModesOfOperation: return "modes of operation 0x6060";
    case c4::kModesDisplay: return "modes display 0x6061";
    case c4::kPositionActual: return "position actual 0x6064";
    case c4::kVelocityActual: return "velocity actual 0x606C";
    case c4::kTargetPosition: return "target position 0x607A";
    case c4::kProfileVelocity: return "profile velocity 0x6081";
    case c4::kProfileAcceleration: return "profile acceleration 0x6083";
    case c4::kProfileDeceleration: return "profile deceleration 0x6084";
    case c4::kErrorCode: return "error code 0x603F";
    default: return "object";
    }
}

int Plan::tpdo_with(uint16_t index) const
{
    for (std::size_t k = 0; k < tpdos.size(); ++k)
        for (const auto& o : tpdos[k].mapping.objects)
            if (o.index == index) return static_cast<int>(k);
    return -1;
}

Plan plan_bring_up(const DriveCapabilities& caps, const PlanOptions& opt)
{
    Plan p;
    std::string missing;
    for (uint16_t i : kMandatoryObjects)
        if (!caps.has(i)) missing += (missing.empty() ? "" : ", ") + std::string(object_name(i));
    if (!missing.empty()) {
        p.fatal = "the drive lacks mandatory " + missing;
        return p;
    }

    for (const auto* list : {&caps.tpdos, &caps.rpdos})
        for (const auto& r : *list)
            if (r.present && !r.remappable) {
                p.flags.fixed_mapping = true;
                p.notes.push_back(pdo_name(r) + " mapping is fixed (" +
                                  (r.refused_code ? describe_abort(r.refused_code) : std::string("read-only")) +
                                  "): the drive's mapping " + list_objects(r.default_mapping));
            }

    // TPDOs: statusword + position in one (the sample), velocity in another if one is left.
    Picker tp(caps.tpdos, caps);
    if (auto sp = tp.any({c4::kStatusword, c4::kPositionActual})) {
        p.tpdos.push_back(*sp);
    } else {
        auto pos = tp.any({c4::kPositionActual});
        auto st = tp.any({c4::kStatusword});
        if (!pos || !st) {
            p.fatal = std::string("no TPDO can carry the ") +
                      (pos ? object_name(c4::kStatusword) : object_name(c4::kPositionActual)) +
                      " (remapping refused and the drive's mappings lack it)";
            return p;
        }
        p.tpdos.push_back(*pos);
        p.tpdos.push_back(*st);
        p.flags.split_status = true;
        p.notes.push_back("statusword and position actual in two TPDOs (TPDO" + std::to_string(st->mapping.number) +
                          ", TPDO" + std::to_string(pos->mapping.number) + "): the PDOs hold too few objects");
    }
    if (!carries(p.tpdos, c4::kVelocityActual)) {
        std::optional<Plan::Pdo> v;
        if (caps.has(c4::kVelocityActual)) v = tp.any({c4::kVelocityActual});
        if (v) {
            p.tpdos.push_back(*v);
        } else {
            p.velocity_from_tpdo = false;
            p.flags.velocity_derived = true;
            p.notes.push_back(caps.has(c4::kVelocityActual)
                                  ? "no TPDO left for velocity actual 0x606C: velocity derived from position"
                                  : "no velocity actual 0x606C: velocity derived from position");
        }
    }
    const bool sync_only = std::any_of(p.tpdos.begin(), p.tpdos.end(), [&](const Plan::Pdo& t) {
        for (const auto& r : caps.tpdos)
            if (r.number == t.mapping.number && !r.event_timer) return true;
        return false;
    });
    if (sync_only && opt.sync_period_us == 0) {
        p.flags.sync_only = true;
        p.notes.push_back("TPDOs go only on SYNC (no event timer): the host produces SYNC every " +
                          std::to_string(opt.sync_only_period_us / 1000) + " ms");
    }
    p.produce_sync = opt.sync_period_us > 0 || sync_only;
    for (auto& t : p.tpdos) {
        t.mapping.transmission_type = p.produce_sync ? uint8_t{1} : kTransmissionEvent;
        t.mapping.event_timer_ms = p.produce_sync ? uint16_t{0} : static_cast<uint16_t>(opt.tpdo_period_ms);
    }

    // RPDOs: target + controlword (target first), profile velocity.
    Picker rp(caps.rpdos, caps);
    if (auto tc = rp.any({c4::kTargetPosition, c4::kControlword})) {
        p.rpdos.push_back(*tc);
    } else {
        auto t = rp.any({c4::kTargetPosition});
        // A target by SDO arrives after an RPDO would: then the controlword (with the
        // new-set-point edge) goes by SDO too, queued behind it.
        auto c = t ? rp.any({c4::kControlword}) : std::nullopt;
        if (t) p.rpdos.push_back(*t);
        if (c) p.rpdos.push_back(*c);
        p.target_by_sdo = !t;
        p.controlword_by_sdo = !c;
        if (p.target_by_sdo || p.controlword_by_sdo) {
            p.flags.setpoint_sdo = true;
            p.notes.push_back(std::string("no RPDO for the ") +
                              (p.target_by_sdo && p.controlword_by_sdo ? "target position and controlword"
                               : p.target_by_sdo                       ? "target position"
                                                                       : "controlword") +
                              ": written by SDO (fewer set-points per second)");
        }
    }
    if (!carries(p.rpdos, c4::kProfileVelocity)) {
        std::optional<Plan::Pdo> v;
        if (caps.has(c4::kProfileVelocity)) v = rp.any({c4::kProfileVelocity});
        if (v) {
            p.rpdos.push_back(*v);
        } else if (caps.has(c4::kProfileVelocity)) {
            p.profile_velocity_by_sdo = true;
            p.flags.profile_velocity_sdo = true;
            p.notes.push_back("no RPDO left for profile velocity 0x6081: written by SDO when it changes");
        } else {
            p.notes.push_back("no profile velocity 0x6081: the drive moves at its own speed");
        }
    }

    if (!caps.heartbeat_producer) {
        p.use_heartbeat = false;
        p.flags.supervised_by_tpdo = true;
        p.notes.push_back("no heartbeat producer 0x1017: the node is supervised by its TPDO stream");
    }
    if (!caps.has(c4::kProfileAcceleration) || !caps.has(c4::kProfileDeceleration)) {
        p.write_acceleration = false;
        p.flags.no_acceleration = true;
        p.notes.push_back("no profile acceleration/deceleration 0x6083/0x6084: the drive's own ramp");
    }
    p.check_supported_modes = caps.supported_modes.has_value();
    return p;
}

DriveCapabilities full_capabilities()
{
    DriveCapabilities c;
    c.supported_modes = 0x5;
    for (uint16_t i : {c4::kControlword, c4::kStatusword, c4::kModesOfOperation, c4::kModesDisplay, c4::kPositionActual,
                       c4::kVelocityActual, c4::kTargetPosition, c4::kProfileVelocity, c4::kProfileAcceleration,
                       c4::kProfileDeceleration})
        c.objects.insert(i);
    for (int n = 1; n <= 4; ++n) {
        PdoResource t;
        t.transmit = true;
        t.number = n;
        t.present = true;
        c.tpdos.push_back(t);
        PdoResource r = t;
        r.transmit = false;
        c.rpdos.push_back(r);
    }
    return c;
}

std::string describe(const DriveCapabilities& c)
{
    std::string s;
    if (c.identity.present)
        s += "identity (0x1018): vendor " + hex32(c.identity.vendor_id) + ", product " + hex32(c.identity.product_code) +
             ", revision " + hex32(c.identity.revision) + ", serial " + hex32(c.identity.serial) + "\n";
    else
        s += "identity (0x1018): not readable\n";
    s += "supported modes (0x6502): " + (c.supported_modes ? hex32(*c.supported_modes) : std::string("absent")) + "\n";
    s += "objects:";
    for (uint16_t i : {c4::kControlword, c4::kStatusword, c4::kModesOfOperation, c4::kModesDisplay, c4::kPositionActual,
                       c4::kVelocityActual, c4::kTargetPosition, c4::kProfileVelocity, c4::kProfileAcceleration,
                       c4::kProfileDeceleration})
        s += " " + hex16(i) + (c.has(i) ? "" : "(absent)");
    s += "\nheartbeat producer 0x1017: " + std::string(c.heartbeat_producer ? "yes" : "no") +
         "; node guarding 0x100C: " + (c.node_guarding ? "yes" : "no") + "\n";
    for (const auto* list : {&c.tpdos, &c.rpdos})
        for (const auto& r : *list) {
            s += pdo_name(r) + ": ";
            if (!r.present) {
                s += "absent\n";
                continue;
            }
            s += "COB-ID " + hex32(r.cob_id) + ((r.cob_id & 0x80000000u) ? " (disabled)" : "") + ", mapping " +
                 list_objects(r.default_mapping) + ", " +
                 (r.remappable ? "remappable, up to " + std::to_string(r.max_objects) + " objects"
                               : "fixed (" + (r.refused_code ? describe_abort(r.refused_code) : std::string("read-only")) + ")");
            if (r.transmit) s += r.event_timer ? ", event timer" : ", SYNC only";
            s += "\n";
        }
    for (uint32_t e : c.unmappable) s += "cannot be mapped: " + hex32(e) + "\n";
    return s;
}

std::string describe(const Plan& p)
{
    if (!p.ok()) return "plan: cannot run: " + p.fatal + "\n";
    std::string s = "plan:\n";
    for (const auto* list : {&p.tpdos, &p.rpdos})
        for (const auto& d : *list) {
            s += std::string("  ") + (d.mapping.transmit ? "TPDO" : "RPDO") + std::to_string(d.mapping.number) + " = " +
                 list_objects(d.mapping.objects) + (d.write_mapping ? " (mapped)" : " (the drive's mapping)");
            if (d.mapping.transmit)
                s += d.mapping.transmission_type == kTransmissionEvent
                         ? ", every " + std::to_string(d.mapping.event_timer_ms) + " ms"
                         : ", every SYNC";
            s += "\n";
        }
    if (p.target_by_sdo) s += "  target position by SDO\n";
    if (p.controlword_by_sdo) s += "  controlword by SDO\n";
    if (p.profile_velocity_by_sdo) s += "  profile velocity by SDO when it changes\n";
    s += std::string("  supervision: ") + (p.use_heartbeat ? "heartbeat 0x1017" : "the TPDO stream") + "\n";
    if (p.produce_sync) s += "  the host produces SYNC\n";
    if (p.notes.empty()) s += "  no degradation\n";
    for (const auto& n : p.notes) s += "  degraded: " + n + "\n";
    return s;
}

}  // namespace ugv::canopen
