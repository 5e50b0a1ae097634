#include "servo_messages.hpp"

namespace ugv::servo_daemon {

nodscan::NodCommand from_message(const servo_command_t& m, double scan_period_s)
{
    nodscan::NodCommand c;
    switch (m.profile) {
    case servo_command_t::PROFILE_STOP: c.kind = nodscan::NodKind::stop; break;
    case servo_command_t::PROFILE_HOLD: c.kind = nodscan::NodKind::hold; break;
    case servo_command_t::PROFILE_CONSTANT_RATE: c.kind = nodscan::NodKind::constant_rate; break;
    case servo_command_t::PROFILE_UNIFORM_GROUND_SPACING: c.kind = nodscan::NodKind::uniform_ground_spacing; break;
    default: c.kind = static_cast<nodscan::NodKind>(m.profile); break;  // refused by check_command
    }
    c.hold_angle_rad = m.hold_angle;
    c.min_tilt_rad = m.min_tilt;
    c.max_tilt_rad = m.max_tilt;
    c.rate_rad_s = m.rate;
    c.ground_spacing_m = m.ground_spacing;
    c.sensor_height_m = m.sensor_height;
    c.scan_period_s = scan_period_s;
    return c;
}

servo_state_t to_message(const canopen::DriveSample& s, nodscan::NodKind profile, uint16_t fault_code, int64_t seq)
{
    servo_state_t m;
    m.utime = s.utime;
    m.seq = seq;
    m.angle = s.angle_rad;
    m.velocity = s.velocity_rad_s;
    m.target = s.target_rad;
    m.profile = static_cast<int8_t>(profile);
    m.cia402_state = static_cast<int8_t>(s.state);
    m.statusword = static_cast<int16_t>(s.statusword);
    m.fault = s.state == canopen::cia402::State::fault || s.state == canopen::cia402::State::fault_reaction_active;
    m.fault_code = fault_code;
    return m;
}

}  // namespace ugv::servo_daemon
