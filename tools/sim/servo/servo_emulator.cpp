#include "servo_emulator.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <utility>

#include "ugv/canopen/emcy.hpp"
#include "ugv/canopen/ids.hpp"
#include "ugv/canopen/sdo.hpp"

namespace ugv::sim::servo {

namespace co = ugv::canopen;
namespace c402 = ugv::canopen::cia402;
using c402::State;

namespace {
constexpr int64_t kPhysicsStepUs = 1000;  // the position loop runs at 1 kHz
}

DriveEmulator::DriveEmulator(DriveModel model) : model_(model), node_(model.node_id)
{
    od_.reset_defaults(node_, model_.shape);
    position_ = model.initial_position_counts;
    move_target_ = position_;
}

void DriveEmulator::send(const io::CanFrame& f)
{
    if (now_us_ < off_bus_until_us_) return;
    out_.push_back(f);
}

std::vector<io::CanFrame> DriveEmulator::take_outgoing() { return std::exchange(out_, {}); }

void DriveEmulator::power_on(int64_t now_us)
{
    powered_ = true;
    now_us_ = now_us;
    reboot(false, now_us);
}

void DriveEmulator::reboot(bool communication_only, int64_t now_us)
{
    if (communication_only) {
        od_.reset_communication(node_, model_.shape);
    } else {
        const double pos = position_;
        od_.reset_defaults(node_, model_.shape);
        position_ = pos;  // the axis does not move because the electronics restarted
        velocity_ = 0.0;
        move_target_ = position_;
        moving_ = false;
        controlword_ = 0;
        error_code_ = 0;
        state_ = State::not_ready_to_switch_on;
        state_since_us_ = now_us;
    }
    nmt_ = co::NmtState::pre_operational;
    send(co::encode_heartbeat(node_, co::NmtState::boot_up));
    next_heartbeat_us_ = now_us;
    for (auto& t : tpdo_next_us_) t = now_us;
    for (auto& s : sync_count_) s = 0;
    update_statusword();
}

void DriveEmulator::drop_off_bus(int64_t duration_us, int64_t now_us) { off_bus_until_us_ = now_us + duration_us; }

void DriveEmulator::raise_fault(uint16_t error_code, int64_t now_us)
{
    if (state_ == State::fault || state_ == State::fault_reaction_active) return;
    error_code_ = error_code;
    od_.set(0x603F, 0, error_code);
    od_.set(0x1001, 0, 0x01);  // generic error
    state_ = State::fault_reaction_active;
    state_since_us_ = now_us;
    move_target_ = position_;  // brake
    update_statusword();
    co::Emergency e;
    e.error_code = error_code;
    e.error_register = 0x01;
    send(co::encode_emcy(node_, e));
}

void DriveEmulator::on_frame(const io::CanFrame& f, int64_t now_us)
{
    if (!powered_ || now_us < off_bus_until_us_ || f.extended) return;
    // What fell due before the frame happens first: jumping the clock to the frame's time
    // would skip the physics steps and the TPDOs of a stretch the host process was not
    // scheduled (a simulator serviced 50 ms late lost four of every five TPDOs of it).
    advance(now_us);
    now_us_ = std::max(now_us_, now_us);
    if (auto cmd = co::decode_nmt(f, node_)) {
        switch (*cmd) {
        case co::NmtCommand::start: nmt_ = co::NmtState::operational; break;
        case co::NmtCommand::stop: nmt_ = co::NmtState::stopped; break;
        case co::NmtCommand::enter_pre_operational: nmt_ = co::NmtState::pre_operational; break;
        case co::NmtCommand::reset_node: reboot(false, now_us); break;
        case co::NmtCommand::reset_communication: reboot(true, now_us); break;
        }
        return;
    }
    if (nmt_ == co::NmtState::stopped) return;  // only NMT in Stopped
    if (f.id == co::kSdoRequestBase + node_) {
        on_sdo(f);
        return;
    }
    if (f.id == co::kSyncId && f.dlc == 0) {
        on_sync();
        return;
    }
    if (nmt_ != co::NmtState::operational) return;
    for (int n = 0; n < 4; ++n) {
        if (!od_.find(static_cast<uint16_t>(0x1400 + n), 1)) continue;
        const uint32_t cob = od_.get(static_cast<uint16_t>(0x1400 + n), 1);
        if ((cob & 0x80000000u) == 0 && (cob & 0x7FF) == f.id && !f.rtr) on_rpdo(n, f);
    }
}

uint32_t DriveEmulator::check_write(uint16_t index, uint8_t sub, uint32_t value, int size) const
{
    const OdEntry* e = od_.find(index, sub);
    if (!e) return od_.find(index, 0) || od_.find(index, 1) ? co::abort_code::no_subindex : co::abort_code::no_object;
    if (e->access == Access::ro) return co::abort_code::read_only;
    if (size != 0 && size != e->size) return co::abort_code::length_mismatch;
    const bool rpdo_map = index >= 0x1600 && index <= 0x1603;
    const bool tpdo_map = index >= 0x1A00 && index <= 0x1A03;
    if (rpdo_map || tpdo_map) {
        // Mapping may change only while the PDO is disabled (COB-ID bit 31 set).
        const uint16_t comm = static_cast<uint16_t>(index - 0x200);
        if ((od_.get(comm, 1) & 0x80000000u) == 0) return co::abort_code::device_state;
        if (sub == 0) {
            if (value > 8) return co::abort_code::value_range;
            if (!od_.find(index, static_cast<uint8_t>(value))) return co::abort_code::mapping_too_long;
            int bits = 0;
            for (uint8_t s = 1; s <= value; ++s) bits += static_cast<int>(od_.get(index, s) & 0xFF);
            if (bits > 64) return co::abort_code::mapping_too_long;
        } else {
            if (od_.get(index, 0) != 0) return co::abort_code::device_state;  // count must be 0 first
            const OdEntry* target = od_.find(static_cast<uint16_t>(value >> 16), static_cast<uint8_t>((value >> 8) & 0xFF));
            if (!target) return co::abort_code::no_object;
            if (!target->mappable || static_cast<int>(value & 0xFF) != target->size * 8) return co::abort_code::not_mappable;
            if (rpdo_map && target->access == Access::ro) return co::abort_code::not_mappable;
        }
    }
    // A transmission type this PDO cannot do: event-driven without an event timer.
    if (index >= 0x1800 && index <= 0x1803 && sub == 2 && (value == 0xFE || value == 0xFF) && !od_.find(index, 5))
        return co::abort_code::value_range;
    if (index == 0x6060 && static_cast<int8_t>(value & 0xFF) != 1 && static_cast<int8_t>(value & 0xFF) != 3)
        return co::abort_code::value_range;
    return 0;
}

void DriveEmulator::apply_write(uint16_t index, uint8_t sub, uint32_t value)
{
    od_.set(index, sub, value);
    if (index == 0x6040) on_controlword(static_cast<uint16_t>(value), now_us_);
    if (index == 0x6060) od_.set(0x6061, 0, value);  // the mode takes effect at once
    if (index == 0x1017) next_heartbeat_us_ = now_us_;
}

void DriveEmulator::on_sdo(const io::CanFrame& f)
{
    const auto req = co::decode_sdo_request(f, node_);
    if (!req) return;
    const uint32_t server = co::kSdoResponseBase + node_;
    switch (req->kind) {
    case co::SdoRequest::Kind::download: {
        const uint32_t abort = check_write(req->at.index, req->at.subindex, req->value, req->size);
        if (abort) {
            send(co::encode_sdo_abort(server, req->at, abort));
            return;
        }
        apply_write(req->at.index, req->at.subindex, req->value);
        send(co::encode_sdo_download_ack(node_, req->at));
        return;
    }
    case co::SdoRequest::Kind::upload: {
        const OdEntry* e = od_.find(req->at.index, req->at.subindex);
        if (!e) {
            send(co::encode_sdo_abort(server, req->at, co::abort_code::no_object));
        } else if (e->access == Access::wo) {
            send(co::encode_sdo_abort(server, req->at, co::abort_code::write_only));
        } else {
            send(co::encode_sdo_upload_reply(node_, req->at, e->value, e->size));
        }
        return;
    }
    case co::SdoRequest::Kind::abort: return;  // the client gave up; nothing to undo
    case co::SdoRequest::Kind::unsupported:
        send(co::encode_sdo_abort(server, req->at, co::abort_code::bad_command));
        return;
    }
}

void DriveEmulator::on_rpdo(int n, const io::CanFrame& f)
{
    const auto map = static_cast<uint16_t>(0x1600 + n);
    const uint32_t count = od_.get(map, 0);
    std::size_t pos = 0;
    std::optional<uint16_t> cw;
    for (uint8_t s = 1; s <= count; ++s) {
        const uint32_t entry = od_.get(map, s);
        const int bytes = static_cast<int>(entry & 0xFF) / 8;
        if (pos + static_cast<std::size_t>(bytes) > f.dlc) return;  // too short: ignore (a real drive sends EMCY 0x8210)
        uint32_t v = 0;
        for (int b = 0; b < bytes; ++b) v |= static_cast<uint32_t>(f.data[pos++]) << (8 * b);
        const auto index = static_cast<uint16_t>(entry >> 16);
        const auto sub = static_cast<uint8_t>((entry >> 8) & 0xFF);
        if (index == 0x6040) {
            cw = static_cast<uint16_t>(v);  // acted upon after every other mapped object is written
            od_.set(index, sub, v);
        } else {
            apply_write(index, sub, v);
        }
    }
    if (cw) on_controlword(*cw, now_us_);
}

void DriveEmulator::on_controlword(uint16_t cw, int64_t now_us)
{
    const uint16_t prev = controlword_;
    controlword_ = cw;
    const auto cmd = c402::command_from_controlword(cw, prev);
    const State before = state_;
    switch (state_) {
    case State::switch_on_disabled:
        if (cmd == c402::Command::shutdown) state_ = State::ready_to_switch_on;
        break;
    case State::ready_to_switch_on:
        if (cmd == c402::Command::switch_on) state_ = State::switched_on;
        else if (cmd == c402::Command::disable_voltage || cmd == c402::Command::quick_stop) state_ = State::switch_on_disabled;
        break;
    case State::switched_on:
        if (cmd == c402::Command::enable_operation) state_ = State::operation_enabled;
        else if (cmd == c402::Command::shutdown) state_ = State::ready_to_switch_on;
        else if (cmd == c402::Command::disable_voltage || cmd == c402::Command::quick_stop) state_ = State::switch_on_disabled;
        break;
    case State::operation_enabled:
        if (cmd == c402::Command::shutdown) state_ = State::ready_to_switch_on;
        else if (cmd == c402::Command::switch_on) state_ = State::switched_on;
        else if (cmd == c402::Command::disable_voltage) state_ = State::switch_on_disabled;
        else if (cmd == c402::Command::quick_stop) state_ = State::quick_stop_active;
        break;
    case State::quick_stop_active:
        if (cmd == c402::Command::disable_voltage) state_ = State::switch_on_disabled;
        else if (cmd == c402::Command::enable_operation) state_ = State::operation_enabled;
        break;
    case State::fault:
        if (cmd == c402::Command::fault_reset) {
            state_ = State::switch_on_disabled;
            error_code_ = 0;
            od_.set(0x603F, 0, 0);
            od_.set(0x1001, 0, 0);
            send(co::encode_emcy(node_, co::Emergency{}));  // error reset
        }
        break;
    case State::not_ready_to_switch_on:
    case State::fault_reaction_active:
    case State::unknown: break;
    }
    if (state_ != before) {
        state_since_us_ = now_us;
        if (state_ != State::operation_enabled) {
            move_target_ = position_;  // power stage off or stopping: no move in progress
            moving_ = false;
        }
    }
    // Profile position: the set-point handshake on the rising edge of bit 4.
    const bool pp = state_ == State::operation_enabled && static_cast<int8_t>(od_.get(0x6061, 0) & 0xFF) == 1;
    const bool rising = (cw & c402::cw::new_setpoint) && !(prev & c402::cw::new_setpoint);
    if (pp && rising && (!moving_ || (cw & c402::cw::change_immediately) || !setpoint_ack_)) {
        const auto target = static_cast<int32_t>(od_.get(0x607A, 0));
        move_target_ = (cw & c402::cw::relative) ? move_target_ + target : target;
        moving_ = true;
        setpoint_ack_ = true;
        ++setpoints_accepted_;
    }
    if (!(cw & c402::cw::new_setpoint)) setpoint_ack_ = false;
    update_statusword();
}

void DriveEmulator::on_sync()
{
    if (nmt_ != co::NmtState::operational) return;
    for (int n = 0; n < 4; ++n) {
        const auto comm = static_cast<uint16_t>(0x1800 + n);
        if (!od_.find(comm, 1) || (od_.get(comm, 1) & 0x80000000u)) continue;
        const uint32_t type = od_.get(comm, 2);
        if (type == 0 || type > 240) continue;
        if (++sync_count_[n] >= static_cast<int>(type)) {
            sync_count_[n] = 0;
            send_tpdo(n);
        }
    }
}

void DriveEmulator::send_tpdo(int n)
{
    const auto comm = static_cast<uint16_t>(0x1800 + n);
    const auto map = static_cast<uint16_t>(0x1A00 + n);
    io::CanFrame f;
    f.id = od_.get(comm, 1) & 0x7FF;
    std::size_t pos = 0;
    const uint32_t count = od_.get(map, 0);
    for (uint8_t s = 1; s <= count; ++s) {
        const uint32_t entry = od_.get(map, s);
        const uint32_t v = od_.get(static_cast<uint16_t>(entry >> 16), static_cast<uint8_t>((entry >> 8) & 0xFF));
        for (uint32_t b = 0; b < (entry & 0xFF) / 8 && pos < 8; ++b) f.data[pos++] = static_cast<uint8_t>(v >> (8 * b));
    }
    f.dlc = static_cast<uint8_t>(pos);
    send(f);
}

void DriveEmulator::update_statusword()
{
    uint16_t sw = 0;
    switch (state_) {
    case State::not_ready_to_switch_on: sw = 0x0000; break;
    case State::switch_on_disabled: sw = 0x0040; break;
    case State::ready_to_switch_on: sw = 0x0021; break;
    case State::switched_on: sw = 0x0023; break;
    case State::operation_enabled: sw = 0x0027; break;
    case State::quick_stop_active: sw = 0x0007; break;
    case State::fault_reaction_active: sw = 0x000F; break;
    case State::fault: sw = 0x0008; break;
    case State::unknown: break;
    }
    if (state_ != State::not_ready_to_switch_on && state_ != State::switch_on_disabled) sw |= c402::sw::voltage_enabled;
    if (state_ != State::quick_stop_active && state_ != State::not_ready_to_switch_on) sw |= c402::sw::quick_stop;
    sw |= 1u << 9;  // remote: the drive obeys the bus
    const bool halted = (controlword_ & c402::cw::halt) != 0;
    const bool still = std::fabs(velocity_) < 1.0;
    if (still && (halted || std::fabs(move_target_ - position_) <= model_.target_window_counts)) sw |= c402::sw::target_reached;
    if (setpoint_ack_) sw |= c402::sw::setpoint_acknowledge;
    statusword_ = sw;
    od_.set(0x6041, 0, sw);
}

void DriveEmulator::step_motion(double dt)
{
    const bool enabled = state_ == State::operation_enabled;
    const bool braking = state_ == State::fault_reaction_active || state_ == State::quick_stop_active;
    const double vmax = std::min<double>(od_.get(0x6081, 0), model_.max_velocity_counts_s);
    // A drive without 0x6083/0x6084 ramps at its own limit.
    const double accel = od_.find(0x6083, 0) ? std::min<double>(od_.get(0x6083, 0), model_.max_acceleration_counts_s2)
                                             : model_.max_acceleration_counts_s2;
    const double decel = od_.find(0x6084, 0) ? std::min<double>(od_.get(0x6084, 0), model_.max_acceleration_counts_s2)
                                             : model_.max_acceleration_counts_s2;
    double desired = 0.0;
    if (enabled && !(controlword_ & c402::cw::halt)) {
        const double e = move_target_ - position_;
        // The fastest speed from which the target can still be reached with this deceleration.
        desired = std::copysign(std::min(vmax, std::sqrt(2.0 * std::max(decel, 1.0) * std::fabs(e))), e);
    }
    if (!enabled && !braking) {
        velocity_ = 0.0;  // power stage off: the brake holds the axis
    } else {
        const double a = (std::fabs(desired) > std::fabs(velocity_) && desired * velocity_ >= 0.0) ? accel : decel;
        const double dv = std::clamp(desired - velocity_, -a * dt, a * dt);
        velocity_ += dv;
        const double before = move_target_ - position_;
        position_ += velocity_ * dt;
        const double after = move_target_ - position_;
        if (enabled && before * after <= 0.0 && std::fabs(velocity_) <= a * dt * 2.0) {
            position_ = move_target_;  // arrived
            velocity_ = 0.0;
        }
    }
    if (moving_ && std::fabs(move_target_ - position_) <= model_.target_window_counts && std::fabs(velocity_) < 1.0)
        moving_ = false;
    od_.set(0x6064, 0, static_cast<uint32_t>(static_cast<int32_t>(std::floor(position_))));  // encoder counts
    od_.set(0x606C, 0, static_cast<uint32_t>(static_cast<int32_t>(std::lround(velocity_))));
}

void DriveEmulator::advance(int64_t now_us)
{
    if (!powered_) return;
    while (now_us_ + kPhysicsStepUs <= now_us) {
        now_us_ += kPhysicsStepUs;
        step_motion(kPhysicsStepUs * 1e-6);
        if (state_ == State::not_ready_to_switch_on && now_us_ - state_since_us_ >= model_.self_test_us) {
            state_ = State::switch_on_disabled;
            state_since_us_ = now_us_;
        }
        if (state_ == State::fault_reaction_active && now_us_ - state_since_us_ >= model_.fault_reaction_us &&
            std::fabs(velocity_) < 1.0) {
            state_ = State::fault;
            state_since_us_ = now_us_;
        }
        update_statusword();

        const int64_t hb_ms = od_.get(0x1017, 0);
        if (hb_ms > 0 && now_us_ >= next_heartbeat_us_) {
            send(co::encode_heartbeat(node_, nmt_));
            next_heartbeat_us_ = next_period(next_heartbeat_us_, hb_ms * 1000);
        }
        if (nmt_ == co::NmtState::operational) {
            for (int n = 0; n < 4; ++n) {
                const auto comm = static_cast<uint16_t>(0x1800 + n);
                if (!od_.find(comm, 1) || (od_.get(comm, 1) & 0x80000000u)) continue;
                const uint32_t type = od_.get(comm, 2);
                const int64_t timer_ms = od_.get(comm, 5);
                if ((type == 0xFE || type == 0xFF) && timer_ms > 0 && now_us_ >= tpdo_next_us_[n]) {
                    send_tpdo(n);
                    tpdo_next_us_[n] = next_period(tpdo_next_us_[n], timer_ms * 1000);
                }
            }
        }
    }
}

}  // namespace ugv::sim::servo
