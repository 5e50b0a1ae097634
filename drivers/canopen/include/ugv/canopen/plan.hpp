// What a CiA 402 drive offers (read by SDO before anything is configured) and the bring-up
// plan made from it: a pure function, capabilities in, plan out, so every drive shape is
// tested without I/O. Drives differ: one to four PDOs, fixed (read-only) default mappings,
// a limit on the objects per PDO, no heartbeat producer (0x1017), TPDOs that go only on SYNC.
// Only a missing mandatory object (0x6040, 0x6041, 0x6060, 0x6064, 0x607A) makes the plan
// fail; everything else degrades (Plan::flags, one note per degradation).
#pragma once

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "ugv/canopen/pdo.hpp"

namespace ugv::canopen {

struct DriveIdentity
{
    bool present = false;  // 0x1018 answered
    uint32_t vendor_id = 0, product_code = 0, revision = 0, serial = 0;
};

// One TPDO or RPDO as the drive reports it.
struct PdoResource
{
    bool transmit = true;
    int number = 1;                  // 1..4
    bool present = false;            // its communication parameter (0x1400/0x1800 + n) answered
    uint32_t cob_id = 0;             // as read (bit 31: not valid)
    bool remappable = true;          // mapping writes accepted (false after 0x06010002 etc.)
    uint32_t refused_code = 0;       // the abort that refused remapping (0 = none seen)
    int max_objects = 8;             // mapping entries the PDO has (sub-indices that answer)
    bool event_timer = true;         // TPDO sub 5 exists and event transmission is accepted
    std::vector<MappedObject> default_mapping;  // as read from 0x1600/0x1A00 + n
    bool contains(uint16_t index) const;
};

struct DriveCapabilities
{
    DriveIdentity identity;
    std::optional<uint32_t> supported_modes;  // 0x6502 (absent on some drives)
    std::set<uint16_t> objects;               // the CiA 402 objects that answered an SDO read
    std::set<uint32_t> unmappable;            // mapping entries refused with 0x06040041
    bool heartbeat_producer = true;           // 0x1017 exists
    bool node_guarding = false;               // 0x100C exists
    std::vector<PdoResource> tpdos, rpdos;    // every number 1..4 probed, present or not
    bool has(uint16_t index) const { return objects.count(index) != 0; }
};

// The objects a profile-position nod cannot run without.
inline constexpr uint16_t kMandatoryObjects[] = {0x6041, 0x6040, 0x6064, 0x607A, 0x6060};
const char* object_name(uint16_t index);

// Each degradation the plan can contain (STATUS_SERVO shows them as 0/1 counters).
struct PlanFlags
{
    bool fixed_mapping = false;          // a PDO runs its drive-given mapping (remap refused)
    bool split_status = false;           // statusword and position in two TPDOs (object limit)
    bool velocity_derived = false;       // no TPDO for 0x606C: velocity from position
    bool profile_velocity_sdo = false;   // no RPDO for 0x6081: written by SDO when it changes
    bool setpoint_sdo = false;           // target / controlword written by SDO (no RPDO for them)
    bool supervised_by_tpdo = false;     // no 0x1017: the TPDO stream is the node's life sign
    bool sync_only = false;              // TPDOs only on SYNC: the host produces SYNC
    bool no_acceleration = false;        // 0x6083/0x6084 missing: the drive's own ramp
};

struct Plan
{
    // PDOs the session uses; write_mapping false: the drive's mapping as it is.
    struct Pdo
    {
        PdoMapping mapping;
        bool write_mapping = true;
    };
    std::vector<Pdo> tpdos, rpdos;
    bool produce_sync = false;
    bool use_heartbeat = true;
    bool profile_velocity_by_sdo = false;
    bool target_by_sdo = false;
    bool controlword_by_sdo = false;
    bool velocity_from_tpdo = true;
    bool write_acceleration = true;
    bool check_supported_modes = true;
    PlanFlags flags;
    std::vector<std::string> notes;  // one line per degradation
    std::string fatal;               // non-empty: the plan cannot run (names what is missing)

    bool ok() const { return fatal.empty(); }
    // The TPDO (index into tpdos) carrying an object, or -1.
    int tpdo_with(uint16_t index) const;
};

struct PlanOptions
{
    int tpdo_period_ms = 10;   // event timer
    int64_t sync_period_us = 0;  // > 0: the host produces SYNC (configured), TPDOs on every SYNC
    int64_t sync_only_period_us = 10'000;  // SYNC period when the drive can only do SYNC
};

Plan plan_bring_up(const DriveCapabilities& caps, const PlanOptions& options);

// What the emulator starts with and a drive with every resource reports (tests, --probe).
DriveCapabilities full_capabilities();

// Multi-line human description (ugv-servo --probe).
std::string describe(const DriveCapabilities& caps);
std::string describe(const Plan& plan);

}  // namespace ugv::canopen
