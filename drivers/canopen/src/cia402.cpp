#include "ugv/canopen/cia402.hpp"

namespace ugv::canopen::cia402 {

State state_from_statusword(uint16_t s)
{
    if ((s & 0x4F) == 0x00) return State::not_ready_to_switch_on;
    if ((s & 0x4F) == 0x40) return State::switch_on_disabled;
    if ((s & 0x6F) == 0x21) return State::ready_to_switch_on;
    if ((s & 0x6F) == 0x23) return State::switched_on;
    if ((s & 0x6F) == 0x27) return State::operation_enabled;
    if ((s & 0x6F) == 0x07) return State::quick_stop_active;
    if ((s & 0x4F) == 0x0F) return State::fault_reaction_active;
    if ((s & 0x4F) == 0x08) return State::fault;
    return State::unknown;
}

const char* to_string(State s)
{
    switch (s) {
    case State::unknown: return "unknown";
    case State::not_ready_to_switch_on: return "not ready to switch on";
    case State::switch_on_disabled: return "switch on disabled";
    case State::ready_to_switch_on: return "ready to switch on";
    case State::switched_on: return "switched on";
    case State::operation_enabled: return "operation enabled";
    case State::quick_stop_active: return "quick stop active";
    case State::fault_reaction_active: return "fault reaction active";
    case State::fault: return "fault";
    }
    return "?";
}

Command command_from_controlword(uint16_t c, uint16_t previous)
{
    // Fault reset acts on the rising edge of bit 7 and takes precedence.
    if ((c & 0x80) && !(previous & 0x80)) return Command::fault_reset;
    if (c & 0x80) return Command::none;
    if ((c & 0x02) == 0) return Command::disable_voltage;                // xxxx xx0x
    if ((c & 0x06) == 0x02) return Command::quick_stop;                  // xxxx x01x
    if ((c & 0x07) == 0x06) return Command::shutdown;                    // xxxx x110
    if ((c & 0x0F) == 0x07) return Command::switch_on;                   // xxxx 0111 (also disable operation)
    if ((c & 0x0F) == 0x0F) return Command::enable_operation;            // xxxx 1111
    return Command::none;
}

Enabler::Enabler(Options options) : options_(options) {}

void Enabler::set_goal(bool want_enabled, int64_t now_us)
{
    want_enabled_ = want_enabled;
    progress_us_ = now_us;
    retries_ = 0;
    failed_ = false;
    if (state_ != State::fault) command_ = decide(state_);
}

bool Enabler::reached() const
{
    return want_enabled_ ? state_ == State::operation_enabled
                         : (state_ == State::ready_to_switch_on || state_ == State::switch_on_disabled);
}

uint16_t Enabler::decide(State s)
{
    switch (s) {
    case State::switch_on_disabled: return want_enabled_ ? cw::shutdown : command_;
    case State::ready_to_switch_on: return want_enabled_ ? cw::switch_on : cw::shutdown;
    case State::switched_on: return want_enabled_ ? cw::enable_operation : cw::shutdown;
    case State::operation_enabled: return want_enabled_ ? cw::enable_operation : cw::shutdown;
    case State::quick_stop_active: return cw::disable_voltage;  // leaves to switch on disabled
    case State::fault: return cw::disable_voltage;  // the low half of the fault-reset edge
    case State::not_ready_to_switch_on:  // self test: wait
    case State::fault_reaction_active:   // braking: wait for Fault
    case State::unknown: return command_;
    }
    return command_;
}

uint16_t Enabler::on_statusword(uint16_t statusword, int64_t now_us)
{
    const State s = state_from_statusword(statusword);
    if (s != state_) {
        state_ = s;
        progress_us_ = now_us;
        retries_ = 0;
        command_ = decide(s);
    } else if (s == State::fault && command_ == cw::disable_voltage) {
        // The drive has seen bit 7 low while in Fault: raise it (the rising edge resets).
        command_ = cw::fault_reset;
        ++fault_resets_;
    }
    return command_;
}

bool Enabler::check_timeout(int64_t now_us)
{
    if (reached() || failed_) return false;
    if (now_us - progress_us_ <= options_.transition_timeout_us) return false;
    progress_us_ = now_us;
    if (retries_ >= options_.max_retries) {
        failed_ = true;
        return false;
    }
    ++retries_;
    ++retries_total_;
    // Re-send the step (in Fault this starts a fresh reset edge with bit 7 low).
    command_ = decide(state_);
    return true;
}

}  // namespace ugv::canopen::cia402
