// Runs the nod profile on the drive: validates each command against the hard tilt limits
// (refusing what would leave them), and every control tick sends the drive the profile's
// set-point a little ahead of now (the lead covers the set-point handshake's round trip),
// with a profile velocity a little above the profile's own rate so the axis keeps up.
// No I/O, no bus: the daemon feeds it time and the commands it received.
#pragma once

#include <numbers>
#include <optional>
#include <string>

#include "ugv/canopen/drive.hpp"
#include "ugv/nodscan/nod_profile.hpp"

namespace ugv::servo_daemon {

struct NodControllerOptions
{
    nodscan::TiltLimits hard_limits;
    double lead_s = 0.05;             // set-point lead over the profile
    double speed_margin = 1.05;       // profile velocity = margin * |profile rate| ...
    double min_speed_rad_s = 0.05;    // ... but at least this much,
    double catch_up_s = 0.1;          // ... plus the distance still to go over this time
    double hold_speed_rad_s = 0.5;    // moving to a HOLD angle (or a STOP)
    // What a command may ask (beyond nodscan::validate's limits): a constant rate the drive
    // can give, a nod that comes back within max_nod_period_s (a tiny rate or spacing would
    // otherwise stop the nod, unseen), spacings and heights in the config keys' ranges.
    double max_rate_rad_s = 120.0 * std::numbers::pi / 180.0;
    double max_nod_period_s = 120.0;
    double min_ground_spacing_m = 0.001, max_ground_spacing_m = 10.0;
    double min_sensor_height_m = 0.01, max_sensor_height_m = 10.0;
};

// Why a command (from SERVO_COMMAND or the config's default profile) must be refused, or
// nullopt: an unknown profile, anything nodscan::validate refuses, or a value outside the
// options' ranges above.
std::optional<std::string> check_command(const nodscan::NodCommand& command, const NodControllerOptions& options);

class NodController
{
public:
    explicit NodController(NodControllerOptions options);

    // Validates and starts a command at t_s from the servo's current angle. Returns the
    // reason when refused (the running profile then continues unchanged).
    std::optional<std::string> apply(const nodscan::NodCommand& command, double t_s, double current_angle_rad);
    // After a re-initialisation or fault recovery: restart the running profile from where the
    // axis is now, so it is not yanked to where the profile would have been.
    void resume(double t_s, double current_angle_rad);

    // The set-point for time t_s (angle, and the speed to move there with, given where the
    // axis is now: the profile's rate plus a catch-up term, so a lag after a turn-around or
    // a fault does not persist).
    struct Output
    {
        double angle_rad = 0.0;
        double speed_rad_s = 0.0;
    };
    Output update(double t_s, double current_angle_rad) const;

    nodscan::NodKind kind() const { return profile_.command().kind; }
    bool started() const { return started_; }

private:
    NodControllerOptions options_;
    nodscan::NodProfile profile_;
    bool started_ = false;
};

}  // namespace ugv::servo_daemon
