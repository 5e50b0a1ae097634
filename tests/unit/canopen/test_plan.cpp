// The bring-up planner: drive capabilities in, plan out, for each drive shape (no I/O).
#include <catch2/catch.hpp>

#include "ugv/canopen/plan.hpp"
#include "ugv/canopen/sdo.hpp"

using namespace ugv::canopen;

namespace {

std::vector<uint16_t> objects(const PdoMapping& m)
{
    std::vector<uint16_t> v;
    for (const auto& o : m.objects) v.push_back(o.index);
    return v;
}

// Keeps the first n PDOs of each kind.
DriveCapabilities with_pdos(int tpdos, int rpdos)
{
    DriveCapabilities c = full_capabilities();
    for (auto& t : c.tpdos) t.present = t.number <= tpdos;
    for (auto& r : c.rpdos) r.present = r.number <= rpdos;
    return c;
}

void fix(PdoResource& r, std::vector<MappedObject> mapping)
{
    r.remappable = false;
    r.refused_code = abort_code::read_only;
    r.default_mapping = std::move(mapping);
}

}  // namespace

TEST_CASE("Plan: a drive with every resource gets our mapping and no degradation")
{
    const Plan p = plan_bring_up(full_capabilities(), {});
    REQUIRE(p.ok());
    REQUIRE(p.tpdos.size() == 2);
    CHECK(objects(p.tpdos[0].mapping) == std::vector<uint16_t>{0x6041, 0x6064});
    CHECK(p.tpdos[0].mapping.event_timer_ms == 10);
    CHECK(objects(p.tpdos[1].mapping) == std::vector<uint16_t>{0x606C});
    REQUIRE(p.rpdos.size() == 2);
    CHECK(objects(p.rpdos[0].mapping) == std::vector<uint16_t>{0x607A, 0x6040});  // target first
    CHECK(objects(p.rpdos[1].mapping) == std::vector<uint16_t>{0x6081});
    CHECK(p.notes.empty());
    CHECK(p.use_heartbeat);
    CHECK(!p.produce_sync);
}

TEST_CASE("Plan: one TPDO and one RPDO: velocity from position, profile velocity by SDO")
{
    const Plan p = plan_bring_up(with_pdos(1, 1), {});
    REQUIRE(p.ok());
    REQUIRE(p.tpdos.size() == 1);
    CHECK(p.flags.velocity_derived);
    CHECK(!p.velocity_from_tpdo);
    CHECK(p.flags.profile_velocity_sdo);
    CHECK(p.profile_velocity_by_sdo);
    CHECK(p.notes.size() == 2);
}

TEST_CASE("Plan: fixed mappings are used as the drive reports them")
{
    DriveCapabilities c = with_pdos(2, 2);
    fix(c.tpdos[0], {{0x6041, 0, 16}, {0x6064, 0, 32}});
    fix(c.tpdos[1], {{0x6041, 0, 16}, {0x606C, 0, 32}});
    fix(c.rpdos[0], {{0x6040, 0, 16}, {0x607A, 0, 32}});
    fix(c.rpdos[1], {{0x6040, 0, 16}, {0x6060, 0, 8}});
    const Plan p = plan_bring_up(c, {});
    REQUIRE(p.ok());
    CHECK(p.flags.fixed_mapping);
    REQUIRE(p.tpdos.size() == 2);
    CHECK(!p.tpdos[0].write_mapping);
    CHECK(p.tpdo_with(0x606C) == 1);
    REQUIRE(p.rpdos.size() == 1);  // RPDO2 (controlword + mode) carries no profile velocity
    CHECK(objects(p.rpdos[0].mapping) == std::vector<uint16_t>{0x6040, 0x607A});
    CHECK(p.flags.profile_velocity_sdo);
}

TEST_CASE("Plan: a fixed TPDO without the position and no other: cannot run, says what")
{
    DriveCapabilities c = with_pdos(1, 1);
    fix(c.tpdos[0], {{0x6041, 0, 16}});
    const Plan p = plan_bring_up(c, {});
    CHECK(!p.ok());
    CHECK(p.fatal.find("position actual 0x6064") != std::string::npos);
}

TEST_CASE("Plan: one object per PDO splits statusword and position; with one RPDO the set-point goes by SDO")
{
    DriveCapabilities c = full_capabilities();
    for (auto* l : {&c.tpdos, &c.rpdos})
        for (auto& r : *l) r.max_objects = 1;
    Plan p = plan_bring_up(c, {});
    REQUIRE(p.ok());
    CHECK(p.flags.split_status);
    CHECK(p.tpdos.size() == 3);
    CHECK(p.tpdo_with(0x6041) != p.tpdo_with(0x6064));
    CHECK(objects(p.rpdos[0].mapping) == std::vector<uint16_t>{0x607A});
    CHECK(objects(p.rpdos[1].mapping) == std::vector<uint16_t>{0x6040});
    CHECK(!p.flags.setpoint_sdo);

    for (auto& r : c.rpdos) r.present = r.number == 1;
    p = plan_bring_up(c, {});
    REQUIRE(p.ok());
    CHECK(p.flags.setpoint_sdo);
    CHECK(!p.target_by_sdo);  // RPDO1 takes the target ...
    CHECK(p.controlword_by_sdo);
    CHECK(p.profile_velocity_by_sdo);
}

TEST_CASE("Plan: an object that cannot be mapped, learnt from 0x06040041, is left to another way")
{
    DriveCapabilities c = full_capabilities();
    c.unmappable.insert(0x606C0020);
    const Plan p = plan_bring_up(c, {});
    REQUIRE(p.ok());
    CHECK(p.flags.velocity_derived);
    CHECK(p.tpdos.size() == 1);
}

TEST_CASE("Plan: no heartbeat producer, SYNC-only TPDOs, no acceleration objects")
{
    DriveCapabilities c = full_capabilities();
    c.heartbeat_producer = false;
    for (auto& t : c.tpdos) t.event_timer = false;
    c.objects.erase(0x6083);
    const Plan p = plan_bring_up(c, {});
    REQUIRE(p.ok());
    CHECK(p.flags.supervised_by_tpdo);
    CHECK(!p.use_heartbeat);
    CHECK(p.flags.sync_only);
    CHECK(p.produce_sync);
    CHECK(p.tpdos[0].mapping.transmission_type == 1);
    CHECK(p.flags.no_acceleration);
    CHECK(!p.write_acceleration);
    CHECK(p.notes.size() == 3);
}

TEST_CASE("Plan: only a missing mandatory object is fatal, and the plan names each")
{
    for (uint16_t index : kMandatoryObjects) {
        DriveCapabilities c = full_capabilities();
        c.objects.erase(index);
        const Plan p = plan_bring_up(c, {});
        CHECK(!p.ok());
        CHECK(p.fatal == std::string("the drive lacks mandatory ") + object_name(index));
    }
    DriveCapabilities c = full_capabilities();
    for (int index : {0x606C, 0x6081, 0x6083, 0x6084, 0x6061}) c.objects.erase(static_cast<uint16_t>(index));
    CHECK(plan_bring_up(c, {}).ok());
}
