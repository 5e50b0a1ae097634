// The CANopen session (drivers/canopen) and the nod controller (daemons/servo) against the
// emulated drive (tools/sim/servo), exchanging frames directly in simulated time.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "nod_controller.hpp"
#include "servo_emulator.hpp"
#include "ugv/canopen/drive.hpp"

using namespace ugv;
using canopen::Drive;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

struct Bench
{
    canopen::DriveConfig config;
    sim::servo::DriveModel model;
    std::unique_ptr<sim::servo::DriveEmulator> emulator;
    std::unique_ptr<Drive> drive;
    int64_t now = 1'000'000;
    std::vector<canopen::DriveSample> samples;

    Bench()
    {
        config.node_id = 5;
        config.units = canopen::UnitConversion{4096.0, 50.0, 1000, 1};
        config.min_angle_rad = -10 * kDeg;
        config.max_angle_rad = 40 * kDeg;
        config.max_velocity_rad_s = 2.0;
        config.acceleration_rad_s2 = 30.0;
        model.node_id = 5;
        model.initial_position_counts = 1000;  // at the zero offset: level
        emulator = std::make_unique<sim::servo::DriveEmulator>(model);
        drive = std::make_unique<Drive>(config);
        emulator->power_on(now);
    }

    // One millisecond of bus time: both sides exchange what they have.
    void step()
    {
        now += 1000;
        emulator->advance(now);
        for (const auto& f : emulator->take_outgoing()) drive->on_frame(f, now, now);
        drive->tick(now);
        for (const auto& f : drive->take_outgoing()) emulator->on_frame(f, now);
        for (const auto& s : drive->take_samples()) samples.push_back(s);
    }

    double t() const { return static_cast<double>(now) * 1e-6; }

    bool run_until(const std::function<bool()>& done, int64_t max_us)
    {
        const int64_t end = now + max_us;
        while (now < end) {
            step();
            if (done()) return true;
        }
        return false;
    }
};

}  // namespace

TEST_CASE("Session configures the emulated drive and reaches Operation Enabled")
{
    Bench b;
    const int64_t t0 = b.now;
    b.drive->start(b.now);
    REQUIRE(b.run_until([&] { return b.drive->operational(); }, 2'000'000));
    std::printf("emulated drive: Operation Enabled after %.0f ms of bus time, %llu SDO aborts (the probe's)\n",
                static_cast<double>(b.now - t0) * 1e-3, static_cast<unsigned long long>(b.drive->counters().sdo_aborts));
    CHECK(b.drive->plan().notes.empty());
    CHECK(b.emulator->state() == canopen::cia402::State::operation_enabled);
    CHECK(b.emulator->nmt_state() == canopen::NmtState::operational);
    // Its dictionary holds the mapping the session wrote.
    CHECK(b.emulator->dictionary().get(0x1A00, 2) == 0x60640020u);
    CHECK(b.emulator->dictionary().get(0x1800, 5) == 10u);
    CHECK(b.emulator->dictionary().get(0x1017, 0) == 100u);
    CHECK(b.emulator->dictionary().get(0x6061, 0) == 1u);
    // The target was set to where the axis stood: enabling does not move it.
    CHECK(b.emulator->target_counts() == 1000);
    CHECK(b.emulator->position_counts() == 1000.0);
    CHECK(b.drive->counters().sdo_timeouts == 0);
}

TEST_CASE("The session plans for each emulated drive shape, enables it and gets 100 Hz samples of a moving axis")
{
    struct Case
    {
        const char* name;
        sim::servo::DriveShape shape;
        int replans;  // refused writes the lean probe learns from (each PDO of a fixed set in turn)
    };
    sim::servo::DriveShape one{};
    one.tpdos = 1;
    one.rpdos = 1;
    sim::servo::DriveShape fixed{};
    fixed.fixed_mapping = true;
    sim::servo::DriveShape single{};
    single.max_mapped = 1;
    single.rpdos = 1;
    sim::servo::DriveShape sync{};
    sync.sync_only = true;
    sync.heartbeat = false;
    for (const Case& c : {Case{"one TPDO, one RPDO", one, 0}, Case{"fixed mappings", fixed, 8},
                          Case{"one object per PDO, one RPDO", single, 5}, Case{"SYNC only, no heartbeat", sync, 0}}) {
        INFO(c.name);
        Bench b;
        b.model.shape = c.shape;
        b.emulator = std::make_unique<sim::servo::DriveEmulator>(b.model);
        b.emulator->power_on(b.now);
        b.drive->start(b.now);
        REQUIRE(b.run_until([&] { return b.drive->operational(); }, 3'000'000));
        CHECK(b.drive->counters().replans == static_cast<uint64_t>(c.replans));
        b.samples.clear();
        for (int i = 0; i < 1000; ++i) {
            b.drive->command(10 * kDeg, 1.0);
            b.step();
        }
        CHECK(b.samples.size() >= 99);
        CHECK(b.samples.size() <= 101);
        CHECK(b.samples.back().angle_rad == Approx(10 * kDeg).margin(0.2 * kDeg));
        CHECK(b.drive->counters().sdo_timeouts == 0);
    }
}

TEST_CASE("Position samples arrive at 100 Hz with the TPDO event timer, and with SYNC")
{
    for (int64_t sync_us : {int64_t{0}, int64_t{10'000}}) {
        Bench b;
        b.config.sync_period_us = sync_us;
        b.drive = std::make_unique<Drive>(b.config);
        b.drive->start(b.now);
        REQUIRE(b.run_until([&] { return b.drive->operational(); }, 2'000'000));
        b.samples.clear();
        b.run_until([] { return false; }, 1'000'000);
        CHECK(b.samples.size() >= 99);
        CHECK(b.samples.size() <= 101);
    }
}


TEST_CASE("The emulated drive's event timer keeps its cadence when its host process stalls")
{
    // A real drive's timers do not stop when the simulator is not scheduled: serviced 75 ms
    // late, it owes the TPDOs that fell due meanwhile, and they reach the session together.
    Bench b;
    b.drive->start(b.now);
    REQUIRE(b.run_until([&] { return b.drive->operational(); }, 2'000'000));
    b.samples.clear();
    for (int stall = 0; stall < 20; ++stall) {
        // 75 ms after the last service; the session's frames queued meanwhile come first,
        // as the simulator reads its pty before it advances the drive.
        b.now += 75'000;
        b.drive->command(0.1 * (stall % 2), 1.0);
        b.drive->tick(b.now);
        const auto queued = b.drive->take_outgoing();
        REQUIRE_FALSE(queued.empty());
        for (const auto& f : queued) b.emulator->on_frame(f, b.now);
        b.emulator->advance(b.now);
        for (const auto& f : b.emulator->take_outgoing()) b.drive->on_frame(f, b.now, b.now);
        for (const auto& s : b.drive->take_samples()) b.samples.push_back(s);
        b.run_until([] { return false; }, 25'000);
    }
    // 20 x 100 ms of drive time.
    CHECK(b.samples.size() >= 199);
    CHECK(b.samples.size() <= 201);
    CHECK(b.drive->operational());
}

TEST_CASE("A constant-rate nod moves the emulated axis between the limits and never beyond")
{
    Bench b;
    servo_daemon::NodControllerOptions o;
    o.hard_limits = {b.config.min_angle_rad, b.config.max_angle_rad};
    servo_daemon::NodController nod(o);
    nodscan::NodCommand c;
    c.kind = nodscan::NodKind::constant_rate;
    c.min_tilt_rad = 0.0;
    c.max_tilt_rad = 20 * kDeg;
    c.rate_rad_s = 40 * kDeg;  // a full nod per second
    b.drive->start(b.now);
    REQUIRE(b.run_until([&] { return b.drive->operational(); }, 2'000'000));
    REQUIRE_FALSE(nod.apply(c, b.t(), 0.0));
    b.samples.clear();
    for (int i = 0; i < 3000; ++i) {
        const auto out = nod.update(b.t(), b.drive->last_sample()->angle_rad);
        b.drive->command(out.angle_rad, out.speed_rad_s);
        b.step();
    }
    double lo = 1e9, hi = -1e9;
    for (const auto& s : b.samples) {
        if (s.utime < b.now - 2'000'000) continue;  // after the first second
        lo = std::min(lo, s.angle_rad);
        hi = std::max(hi, s.angle_rad);
    }
    CHECK(lo < 2 * kDeg);
    CHECK(hi > 18 * kDeg);
    CHECK(lo > -1 * kDeg);  // the command's range, with a little overshoot at most
    CHECK(hi < 21 * kDeg);
    CHECK(b.drive->counters().setpoints_acknowledged > 50);
    CHECK(b.drive->counters().setpoint_timeouts == 0);
}

TEST_CASE("A fault raised mid-nod is reset, the drive re-enabled and the nod resumes")
{
    Bench b;
    servo_daemon::NodControllerOptions o;
    o.hard_limits = {b.config.min_angle_rad, b.config.max_angle_rad};
    servo_daemon::NodController nod(o);
    nodscan::NodCommand c;
    c.kind = nodscan::NodKind::constant_rate;
    c.min_tilt_rad = 0.0;
    c.max_tilt_rad = 20 * kDeg;
    c.rate_rad_s = 40 * kDeg;
    b.drive->start(b.now);
    REQUIRE(b.run_until([&] { return b.drive->operational(); }, 2'000'000));
    REQUIRE_FALSE(nod.apply(c, b.t(), 0.0));
    auto nod_for = [&](int ms) {
        for (int i = 0; i < ms; ++i) {
            if (b.drive->operational()) {
                const auto out = nod.update(b.t(), b.drive->last_sample()->angle_rad);
                b.drive->command(out.angle_rad, out.speed_rad_s);
            }
            b.step();
        }
    };
    nod_for(700);
    b.emulator->raise_fault(0x8611, b.now);
    REQUIRE(b.run_until([&] { return !b.drive->operational(); }, 200'000));
    REQUIRE(b.run_until([&] { return b.drive->operational(); }, 2'000'000));
    CHECK(b.drive->counters().faults == 1);
    CHECK(b.drive->counters().fault_resets == 1);
    CHECK(b.drive->counters().emcy == 2);  // the fault and the error reset
    CHECK(b.drive->last_emcy_code() == 0x8611);
    nod.resume(b.t(), b.drive->last_sample()->angle_rad);
    b.samples.clear();
    nod_for(1500);
    double lo = 1e9, hi = -1e9;
    for (const auto& s : b.samples) {
        lo = std::min(lo, s.angle_rad);
        hi = std::max(hi, s.angle_rad);
    }
    CHECK(hi - lo > 15 * kDeg);
}

TEST_CASE("The emulated node dropping off the bus is noticed after 3 heartbeats; a restart recovers")
{
    Bench b;
    b.drive->start(b.now);
    REQUIRE(b.run_until([&] { return b.drive->operational(); }, 2'000'000));
    b.emulator->drop_off_bus(1'000'000, b.now);
    const int64_t dropped = b.now;
    REQUIRE(b.run_until([&] { return b.drive->phase() == Drive::Phase::failed; }, 1'000'000));
    CHECK(b.now - dropped > 200'000);
    CHECK(b.now - dropped <= 410'000);
    CHECK(b.drive->counters().heartbeat_losses == 1);
    b.run_until([] { return false; }, 800'000);  // back on the bus
    b.drive->start(b.now);
    REQUIRE(b.run_until([&] { return b.drive->operational(); }, 2'000'000));
}

TEST_CASE("The emulator refuses what a real drive refuses")
{
    Bench b;
    std::vector<io::CanFrame> replies;
    auto sdo = [&](const io::CanFrame& f) {
        b.emulator->on_frame(f, b.now);
        b.emulator->advance(b.now + 1000);
        b.now += 1000;
        for (const auto& r : b.emulator->take_outgoing())
            if (r.id == 0x585) return canopen::decode_sdo_response(r, 5);
        return std::optional<canopen::SdoResponse>{};
    };
    auto r = sdo(canopen::encode_sdo_download(5, {0x6041, 0}, 0, 2));
    REQUIRE(r);
    CHECK(r->kind == canopen::SdoResponse::Kind::abort);
    CHECK(r->value == canopen::abort_code::read_only);
    r = sdo(canopen::encode_sdo_upload(5, {0x2345, 0}));
    CHECK(r->value == canopen::abort_code::no_object);
    r = sdo(canopen::encode_sdo_download(5, {0x6060, 0}, 7, 1));
    CHECK(r->value == canopen::abort_code::value_range);
    // Mapping a PDO that is still enabled is refused.
    r = sdo(canopen::encode_sdo_download(5, {0x1A00, 0}, 0, 1));
    CHECK(r->value == canopen::abort_code::device_state);
    r = sdo(canopen::encode_sdo_upload(5, {0x6502, 0}));
    CHECK(r->kind == canopen::SdoResponse::Kind::upload_data);
    CHECK(r->value == 0x5u);
}

TEST_CASE("The emulated axis following the uniform-spacing profile lays scans evenly on the ground")
{
    Bench b;
    servo_daemon::NodControllerOptions o;
    o.hard_limits = {b.config.min_angle_rad, b.config.max_angle_rad};
    servo_daemon::NodController nod(o);
    const double h = 0.87, spacing = 0.2, period = 1.0 / 37.5;
    nodscan::NodCommand c;
    c.kind = nodscan::NodKind::uniform_ground_spacing;
    c.sensor_height_m = h;
    c.ground_spacing_m = spacing;
    c.scan_period_s = period;
    // 2 m .. 8 m: the fastest tilt rate (1.4 rad/s at 2 m) is within the servo's 2 rad/s.
    c.min_tilt_rad = std::atan2(h, 8.0);
    c.max_tilt_rad = std::atan2(h, 2.0);
    b.drive->start(b.now);
    REQUIRE(b.run_until([&] { return b.drive->operational(); }, 2'000'000));
    REQUIRE_FALSE(nod.apply(c, b.t(), 0.0));
    std::vector<double> hits;
    double next_scan = b.t() + 1.0;  // after the axis has caught up with the profile
    const double end = b.t() + 7.0;
    while (b.t() < end) {
        const auto out = nod.update(b.t(), b.drive->last_sample()->angle_rad);
        b.drive->command(out.angle_rad, out.speed_rad_s);
        b.step();
        if (b.t() >= next_scan) {
            // The axis's true angle at the scan's time (the emulator's, not the last TPDO's).
            hits.push_back(nodscan::ground_distance(
                h, b.config.units.to_rad(static_cast<int64_t>(std::floor(b.emulator->position_counts())))));
            next_scan += period;
        }
    }
    int checked = 0, within = 0;
    for (std::size_t k = 2; k < hits.size(); ++k) {
        const double step = hits[k] - hits[k - 1], previous = hits[k - 1] - hits[k - 2];
        if (step * previous <= 0.0) continue;  // a turn-around at either end of the range
        ++checked;
        within += std::fabs(std::fabs(step) - spacing) <= 0.1 * spacing;
    }
    CHECK(checked > 100);
    // The servo (velocity/acceleration limited, an integer encoder, 100 Hz samples) lags at
    // the turn-arounds; away from them the spacing holds within 10 %.
    CHECK(within >= 0.9 * checked);
}
