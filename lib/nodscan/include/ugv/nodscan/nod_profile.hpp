// Nod profiles of the tilting laser (report section 3.6): the tilt angle as a function of time.
// Angles are tilts below horizontal (rad, positive = nose down, as in servo_state_t).
//   STOP                    stay where the servo is when the command arrives;
//   HOLD(angle)             go to one angle and stay;
//   CONSTANT_RATE           a triangle wave between the tilt limits at a constant rate;
//   UNIFORM_GROUND_SPACING  the rate varies so that successive scans land on flat ground a
//                           constant distance apart (the map's grid size): the ground hit
//                           d = h / tan(theta) moves at ground_spacing / scan_period, so
//                           dtheta/dt = (spacing / T) * sin^2(theta) / h, which is the fact
//                           sheet's dtheta = Dd * h / (h^2 + d^2) per scan.
// Pure: no clock, no I/O. The servo daemon samples it a little ahead of now.
#pragma once

#include <optional>
#include <string>

namespace ugv::nodscan {

// Values match servo_command_t.PROFILE_*.
enum class NodKind : int { stop = 0, hold = 1, constant_rate = 2, uniform_ground_spacing = 3 };

const char* to_string(NodKind kind);

struct TiltLimits
{
    double min_rad = -0.1;
    double max_rad = 0.6;
    bool contains(double a) const { return a >= min_rad && a <= max_rad; }
};

struct NodCommand
{
    NodKind kind = NodKind::stop;
    double hold_angle_rad = 0.0;   // HOLD
    double min_tilt_rad = 0.0;     // nodding range; must lie inside the hard limits
    double max_tilt_rad = 0.0;
    double rate_rad_s = 0.0;       // CONSTANT_RATE
    double ground_spacing_m = 0.0; // UNIFORM_GROUND_SPACING: distance between scans on the ground
    double sensor_height_m = 0.0;  // UNIFORM_GROUND_SPACING: tilt axis above the ground
    double scan_period_s = 0.0;    // UNIFORM_GROUND_SPACING: the laser's scan period
};

// Why a command must be refused (outside the limits, a non-positive rate, ...), or nullopt
// when it is acceptable. The hard limits come from the configuration and are never exceeded.
std::optional<std::string> validate(const NodCommand& command, const TiltLimits& hard_limits);

struct TiltSetpoint
{
    double angle_rad = 0.0;
    double velocity_rad_s = 0.0;  // signed rate of the profile at that time (0 when holding)
};

class NodProfile
{
public:
    // Starts a (validated) command at time t0_s with the servo at current_angle_rad. Nodding
    // profiles start from the current angle (clamped into their range), heading up-range
    // (towards max tilt) first, so the servo is not yanked to one end.
    void start(const NodCommand& command, double t0_s, double current_angle_rad);

    // The set-point at time t_s (>= t0). Always inside [min, max] of the command (and HOLD's
    // angle), never outside the hard limits it was validated against.
    TiltSetpoint at(double t_s) const;

    const NodCommand& command() const { return command_; }
    // The time one full nod (down and up) takes, s; 0 for STOP and HOLD.
    double nod_period_s() const;

private:
    NodCommand command_;
    double t0_s_ = 0.0;
    double hold_rad_ = 0.0;
    double phase0_ = 0.0;  // position along the triangle at t0 (rad or m of travel)
};

// The ground distance at which a ray tilted `tilt_rad` below horizontal from height h meets
// flat ground: h / tan(tilt); +inf for tilt <= 0.
double ground_distance(double sensor_height_m, double tilt_rad);

}  // namespace ugv::nodscan
