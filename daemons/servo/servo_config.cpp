#include "servo_config.hpp"

#include <array>
#include <numbers>
#include <optional>
#include <string>

#include "ugv/io/can_transport.hpp"

namespace ugv::servo_daemon {
namespace {
constexpr double kDeg = std::numbers::pi / 180.0;
// The serial rates of UART slcan bridges (USB CDC adapters ignore the rate).
constexpr std::array<int, 12> kSlcanBauds = {9600,   19200,  38400,   57600,   115200,  230400,
                                             460800, 500000, 921600, 1000000, 2000000, 3000000};

// The BAUD of "slcan:PATH@BAUD" when it is not one of kSlcanBauds (the spec parsed already).
std::optional<std::string> bad_slcan_baud(const std::string& transport)
{
    const auto at = transport.rfind('@');
    if (transport.rfind("slcan:", 0) != 0 || at == std::string::npos) return std::nullopt;
    const std::string baud = transport.substr(at + 1);
    for (const int b : kSlcanBauds)
        if (baud == std::to_string(b)) return std::nullopt;
    std::string list;
    for (const int b : kSlcanBauds) list += (list.empty() ? "" : ", ") + std::to_string(b);
    return "slcan baud " + baud + " is not one of " + list;
}
}  // namespace

ServoConfig read_config(runtime::Config& cfg)
{
    ServoConfig c;
    c.transport = cfg.get_string("transport", c.transport);
    c.bitrate = static_cast<int>(cfg.get_int("bitrate", 500000, {10000, 20000, 50000, 100000, 125000, 250000, 500000,
                                                                  800000, 1000000}));
    try {
        (void)io::make_can_transport(c.transport, c.bitrate);  // checks the spec only; opens nothing
    } catch (const std::invalid_argument& e) {
        cfg.fail("transport", e.what());
    }
    if (auto why = bad_slcan_baud(c.transport)) cfg.fail("transport", *why);
    c.channel = cfg.get_channel("channel", c.channel);
    c.command_channel = cfg.get_channel_regex("command_channel", c.command_channel);

    canopen::DriveConfig& d = c.drive;
    d.node_id = static_cast<uint8_t>(cfg.get_int("node_id", 1, 1, 127));
    d.units.counts_per_rev = cfg.get_double("counts_per_rev", 4096.0, 1.0, 1e9);
    d.units.gear_ratio = cfg.get_double("gear_ratio", 50.0, 1e-3, 1e6);
    d.units.zero_offset = cfg.get_int("zero_offset_counts", 0, INT32_MIN, INT32_MAX);
    d.units.direction = static_cast<int>(cfg.get_int("direction", 1, {-1, 1}));
    const double min_tilt = cfg.get_double("min_tilt_deg", -10.0, -90.0, 90.0) * kDeg;
    const double max_tilt = cfg.get_double("max_tilt_deg", 40.0, -90.0, 90.0) * kDeg;
    if (!(max_tilt > min_tilt)) cfg.fail("max_tilt_deg", "must be greater than min_tilt_deg");
    d.min_angle_rad = min_tilt;
    d.max_angle_rad = max_tilt;
    d.max_velocity_rad_s = cfg.get_double("max_rate_deg_s", 120.0, 1.0, 3600.0) * kDeg;
    d.acceleration_rad_s2 = cfg.get_double("acceleration_deg_s2", 1500.0, 1.0, 1e6) * kDeg;
    d.heartbeat_period_ms = static_cast<int>(cfg.get_int("heartbeat_ms", 100, 10, 5000));
    d.sdo_timeout_us = cfg.get_int("sdo_timeout_ms", 200, 10, 5000) * 1000;
    d.tpdo_period_ms = static_cast<int>(cfg.get_int("tpdo_period_ms", 10, 1, 10));
    d.sync_period_us = cfg.get_int("sync_period_ms", 0, 0, 10) * 1000;
    d.enabler.transition_timeout_us = cfg.get_int("enable_timeout_ms", 500, 10, 10000) * 1000;
    d.enabler.max_retries = static_cast<int>(cfg.get_int("enable_retries", 3, 0, 100));
    // slcan's ASCII lines have no checksum (SocketCAN frames were CRC-checked on the bus).
    d.check_tpdo_plausibility = c.transport.rfind("slcan:", 0) == 0;

    c.nod.hard_limits = {min_tilt, max_tilt};
    c.nod.lead_s = cfg.get_double("setpoint_lead_ms", 50.0, 0.0, 1000.0) * 1e-3;
    c.nod.hold_speed_rad_s = cfg.get_double("hold_rate_deg_s", 30.0, 0.1, 3600.0) * kDeg;
    c.nod.max_rate_rad_s = d.max_velocity_rad_s;
    c.nod.max_nod_period_s = cfg.get_double("max_nod_period_s", 120.0, 1.0, 3600.0);

    runtime::Config p = cfg.section("profile");
    nodscan::NodCommand& n = c.default_profile;
    const std::string kind =
        p.get_enum("kind", "CONSTANT_RATE", {"STOP", "HOLD", "CONSTANT_RATE", "UNIFORM_GROUND_SPACING"});
    n.kind = kind == "STOP" ? nodscan::NodKind::stop
             : kind == "HOLD" ? nodscan::NodKind::hold
             : kind == "CONSTANT_RATE" ? nodscan::NodKind::constant_rate
                                       : nodscan::NodKind::uniform_ground_spacing;
    n.hold_angle_rad = p.get_double("hold_deg", 10.0, -90.0, 90.0) * kDeg;
    n.min_tilt_rad = p.get_double("nod_min_deg", 2.0, -90.0, 90.0) * kDeg;
    n.max_tilt_rad = p.get_double("nod_max_deg", 30.0, -90.0, 90.0) * kDeg;
    n.rate_rad_s = p.get_double("rate_deg_s", 30.0, 0.01, 3600.0) * kDeg;
    n.ground_spacing_m = p.get_double("ground_spacing_m", 0.2, 0.001, 10.0);
    n.sensor_height_m = p.get_double("sensor_height_m", 0.87, 0.01, 10.0);
    n.scan_period_s = p.get_double("scan_period_s", 1.0 / 37.5, 0.001, 10.0);
    if (auto why = check_command(n, c.nod)) p.fail("kind", *why);

    c.control_period_us = cfg.get_int("control_period_ms", 10, 1, 50) * 1000;
    // The TPDO clock fits the least delayed arrival of each half second (io::PeriodicClock):
    // every half second at the latest there must be prompt reads.
    c.frame_wakeup_period_us = cfg.get_int("frame_wakeup_period_ms", 500, 0, 500) * 1000;
    if (c.frame_wakeup_period_us > 0 && c.frame_wakeup_period_us < 100'000)
        cfg.fail("frame_wakeup_period_ms", "must be 0 (wake for every frame) or 100..500");
    return c;
}

}  // namespace ugv::servo_daemon
