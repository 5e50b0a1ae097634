// CiA 402 drive profile: objects, statusword decoding, controlword commands, and the
// enabler that walks a drive to Operation Enabled (with fault reset, timeouts and retries).
#pragma once

#include <cstdint>

namespace ugv::canopen::cia402 {

// Object dictionary indices.
inline constexpr uint16_t kControlword = 0x6040;
inline constexpr uint16_t kStatusword = 0x6041;
inline constexpr uint16_t kModesOfOperation = 0x6060;
inline constexpr uint16_t kModesDisplay = 0x6061;
inline constexpr uint16_t kPositionActual = 0x6064;
inline constexpr uint16_t kVelocityActual = 0x606C;
inline constexpr uint16_t kTargetPosition = 0x607A;
inline constexpr uint16_t kProfileVelocity = 0x6081;
inline constexpr uint16_t kProfileAcceleration = 0x6083;
inline constexpr uint16_t kProfileDeceleration = 0x6084;
inline constexpr uint16_t kSupportedModes = 0x6502;
inline constexpr uint16_t kErrorCode = 0x603F;
inline constexpr uint16_t kHeartbeatProducerTime = 0x1017;  // CiA 301, u16 ms

inline constexpr int8_t kModeProfilePosition = 1;

// Statusword bits.
namespace sw {
inline constexpr uint16_t ready_to_switch_on = 1u << 0;
inline constexpr uint16_t switched_on = 1u << 1;
inline constexpr uint16_t operation_enabled = 1u << 2;
inline constexpr uint16_t fault = 1u << 3;
inline constexpr uint16_t voltage_enabled = 1u << 4;
inline constexpr uint16_t quick_stop = 1u << 5;
inline constexpr uint16_t switch_on_disabled = 1u << 6;
inline constexpr uint16_t warning = 1u << 7;
inline constexpr uint16_t target_reached = 1u << 10;
inline constexpr uint16_t setpoint_acknowledge = 1u << 12;
inline constexpr uint16_t following_error = 1u << 13;
}  // namespace sw

// Controlword: the device-control commands (bits 0-3, 7) and the profile-position bits.
namespace cw {
inline constexpr uint16_t disable_voltage = 0x0000;
inline constexpr uint16_t shutdown = 0x0006;
inline constexpr uint16_t switch_on = 0x0007;
inline constexpr uint16_t enable_operation = 0x000F;
inline constexpr uint16_t quick_stop = 0x0002;
inline constexpr uint16_t fault_reset = 0x0080;  // acts on the rising edge
inline constexpr uint16_t new_setpoint = 1u << 4;
inline constexpr uint16_t change_immediately = 1u << 5;
inline constexpr uint16_t relative = 1u << 6;
inline constexpr uint16_t halt = 1u << 8;
}  // namespace cw

// The values match servo_state_t.STATE_* (0 = unknown).
enum class State : int8_t {
    unknown = 0,
    not_ready_to_switch_on = 1,
    switch_on_disabled = 2,
    ready_to_switch_on = 3,
    switched_on = 4,
    operation_enabled = 5,
    quick_stop_active = 6,
    fault_reaction_active = 7,
    fault = 8,
};

// The state the statusword shows (masks and values of CiA 402).
State state_from_statusword(uint16_t statusword);
const char* to_string(State state);

// Which command of the device-control state machine a controlword is, as a drive sees it
// (bits 0-3 and 7). Used by the emulator.
enum class Command { none, shutdown, switch_on, enable_operation, disable_voltage, quick_stop, disable_operation, fault_reset };
Command command_from_controlword(uint16_t controlword, uint16_t previous_controlword);

// Walks the drive to Operation Enabled, or to Switched-On-Disabled/Ready for a shutdown.
// Feed it every statusword; it answers with the controlword to send (device-control bits
// only; the caller adds the set-point and halt bits). A transition that does not happen
// within transition_timeout_us is re-sent, up to max_retries times, then failed() is set.
// A fault is reset by a rising edge of bit 7 (0x00 then 0x80), counted in fault_resets().
class Enabler
{
public:
    struct Options
    {
        int64_t transition_timeout_us = 500'000;
        int max_retries = 3;
    };
    Enabler() : Enabler(Options{}) {}
    explicit Enabler(Options options);

    // want_enabled = true: towards Operation Enabled; false: towards Ready to Switch On
    // (power stage off).
    void set_goal(bool want_enabled, int64_t now_us);
    // Returns the controlword's device-control bits to send now.
    uint16_t on_statusword(uint16_t statusword, int64_t now_us);
    // Called periodically: re-sends the last command on a timeout. Returns true when the
    // caller must send the controlword again (command() holds it).
    bool check_timeout(int64_t now_us);

    uint16_t command() const { return command_; }
    State state() const { return state_; }
    bool reached() const;
    bool failed() const { return failed_; }
    uint64_t fault_resets() const { return fault_resets_; }
    uint64_t retries() const { return retries_total_; }

private:
    uint16_t decide(State s);

    Options options_;
    bool want_enabled_ = true;
    State state_ = State::unknown;
    uint16_t command_ = cw::disable_voltage;
    int64_t progress_us_ = 0;   // when the state last changed (or the goal was set)
    int retries_ = 0;
    bool failed_ = false;
    uint64_t fault_resets_ = 0;
    uint64_t retries_total_ = 0;
};

}  // namespace ugv::canopen::cia402
