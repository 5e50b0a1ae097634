#include "ugv/canopen/drive.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

#include "ugv/canopen/emcy.hpp"
#include "ugv/canopen/ids.hpp"

namespace ugv::canopen {
namespace {

// Room for what the velocity bound does not cover: encoder quantisation, receive-time jitter.
constexpr double kPositionSlackRad = 0.5 * 3.14159265358979323846 / 180.0;
constexpr double kVelocitySlackRadS = 0.05;

std::string hex_address(SdoAddress at)
{
    char buf[16];
    std::snprintf(buf, sizeof buf, "0x%04X:%02X", at.index, at.subindex);
    return buf;
}

}  // namespace

PdoMapping Drive::tpdo1(const DriveConfig& c)
{
    PdoMapping m;
    m.transmit = true;
    m.number = 1;
    m.transmission_type = c.sync_period_us > 0 ? uint8_t{1} : kTransmissionEvent;
    m.event_timer_ms = c.sync_period_us > 0 ? uint16_t{0} : static_cast<uint16_t>(c.tpdo_period_ms);
    m.objects = {{cia402::kStatusword, 0, 16}, {cia402::kPositionActual, 0, 32}};
    return m;
}

PdoMapping Drive::tpdo2(const DriveConfig& c)
{
    PdoMapping m = tpdo1(c);
    m.number = 2;
    m.objects = {{cia402::kVelocityActual, 0, 32}};
    return m;
}

PdoMapping Drive::rpdo1()
{
    // Target first: the drive writes 0x607A before it sees the new-set-point edge in 0x6040.
    PdoMapping m;
    m.transmit = false;
    m.number = 1;
    m.objects = {{cia402::kTargetPosition, 0, 32}, {cia402::kControlword, 0, 16}};
    return m;
}

PdoMapping Drive::rpdo2()
{
    PdoMapping m;
    m.transmit = false;
    m.number = 2;
    m.objects = {{cia402::kProfileVelocity, 0, 32}};
    return m;
}

const char* Drive::to_string(Phase p)
{
    switch (p) {
    case Phase::idle: return "idle";
    case Phase::configuring: return "configuring";
    case Phase::starting: return "starting";
    case Phase::enabling: return "enabling";
    case Phase::operational: return "operational";
    case Phase::halting: return "halting";
    case Phase::disabling: return "disabling";
    case Phase::stopped: return "stopped";
    case Phase::failed: return "failed";
    }
    return "?";
}

Drive::Drive(DriveConfig config)
    : config_(config),
      node_(config.node_id),
      sdo_(config.node_id, config.sdo_timeout_us, config.sdo_retries),
      heartbeat_(config.node_id, int64_t{config.heartbeat_period_ms} * 1000),
      enabler_(config.enabler),
      setpoint_(config.setpoint_timeout_us),
      tpdo1_(tpdo1(config)),
      tpdo2_(tpdo2(config)),
      rpdo1_(rpdo1()),
      rpdo2_(rpdo2())
{
}

void Drive::event(DriveEvent::Level level, std::string text) { events_.push_back({level, std::move(text)}); }

void Drive::fail(const std::string& why)
{
    phase_ = Phase::failed;
    failure_ = why;
    sdo_.clear();
    event(DriveEvent::Level::error, why);
}

void Drive::start(int64_t now_us)
{
    sdo_.clear();
    failure_.clear();
    config_done_ = false;
    halt_ = false;
    sent_rpdo1_.reset();
    sent_velocity_.reset();
    last_state_ = cia402::State::unknown;
    last_tpdo1_reading_.reset();
    holding_tpdo1_ = false;
    // Without SYNC, TPDO1 comes every event-timer period of the drive's clock.
    tpdo1_clock_ = io::PeriodicClock(config_.tpdo_period_ms * 1e-3, 1, tpdo1_clock_.restarts());
    lost_frames_ = 0;
    frames_since_start_ = 0;
    counters_.fault_resets += enabler_.fault_resets();  // the fresh enabler counts from 0
    enabler_ = cia402::Enabler(config_.enabler);
    phase_ = Phase::configuring;
    phase_us_ = now_us;
    // PDOs must not run while their mapping is rewritten.
    out_.push_back(encode_nmt(NmtCommand::enter_pre_operational, node_));
    queue_configuration();
    event(DriveEvent::Level::info, "configuring node " + std::to_string(node_));
}

void Drive::queue_configuration()
{
    sdo_.read({cia402::kSupportedModes, 0}, [this](const SdoResult& r) {
        if (!r.ok) {
            fail(std::string("SDO read 0x6502:00 ") + (r.timed_out ? "timed out" : "aborted: " + describe_abort(r.abort_code)));
            return;
        }
        if ((r.value & 0x1u) == 0) fail("drive does not support profile position mode (0x6502 = " +
                                        std::to_string(r.value) + ")");
    });
    std::vector<SdoWrite> writes;
    writes.push_back({{cia402::kHeartbeatProducerTime, 0}, static_cast<uint32_t>(config_.heartbeat_period_ms), 2});
    for (const PdoMapping* m : {&tpdo1_, &tpdo2_, &rpdo1_, &rpdo2_}) {
        const auto w = pdo_configuration(*m, node_);
        writes.insert(writes.end(), w.begin(), w.end());
    }
    const uint32_t accel = std::max<uint32_t>(1, config_.units.to_counts_rate(config_.acceleration_rad_s2));
    writes.push_back({{cia402::kModesOfOperation, 0}, static_cast<uint32_t>(cia402::kModeProfilePosition), 1});
    writes.push_back({{cia402::kProfileAcceleration, 0}, accel, 4});
    writes.push_back({{cia402::kProfileDeceleration, 0}, accel, 4});
    for (const auto& w : writes) {
        sdo_.write(w.at, w.value, w.size, [this, w](const SdoResult& r) {
            if (r.ok) return;
            fail("SDO write " + hex_address(w.at) + (r.timed_out ? " timed out" : " aborted: " + describe_abort(r.abort_code)));
        });
    }
    // Mode display must confirm profile position before the drive is enabled.
    sdo_.read({cia402::kModesDisplay, 0}, [this](const SdoResult& r) {
        if (!r.ok) {
            fail(std::string("SDO read 0x6061:00 ") + (r.timed_out ? "timed out" : "aborted: " + describe_abort(r.abort_code)));
            return;
        }
        if (static_cast<int8_t>(r.value & 0xFF) != cia402::kModeProfilePosition) {
            fail("drive did not take profile position mode (0x6061 = " + std::to_string(static_cast<int8_t>(r.value & 0xFF)) + ")");
            return;
        }
        config_done_ = true;
    });
}

void Drive::stop(int64_t now_us)
{
    if (phase_ == Phase::operational || phase_ == Phase::enabling) {
        halt_ = true;
        phase_ = Phase::halting;
        phase_us_ = now_us;
        send_rpdos(true);
    } else if (phase_ != Phase::stopped) {
        sdo_.clear();
        phase_ = Phase::stopped;
    }
}

void Drive::command(double angle_rad, double velocity_rad_s)
{
    if (!std::isfinite(angle_rad)) return;
    const double a = std::clamp(angle_rad, config_.min_angle_rad, config_.max_angle_rad);
    const double v = std::min(std::fabs(std::isfinite(velocity_rad_s) ? velocity_rad_s : 0.0), config_.max_velocity_rad_s);
    // A profile velocity of 0 would never arrive; one count/s is the slowest real move.
    setpoint_.request(config_.units.to_counts(a), std::max<uint32_t>(1, config_.units.to_counts_rate(v)));
}

void Drive::send_rpdos(bool force)
{
    if (!sent_velocity_ || *sent_velocity_ != setpoint_.velocity()) {
        out_.push_back(pack_pdo(rpdo2_, node_, {setpoint_.velocity()}));
        sent_velocity_ = setpoint_.velocity();
    }
    uint16_t cw = enabler_.command();
    if (phase_ == Phase::operational || phase_ == Phase::halting) {
        cw = static_cast<uint16_t>(cw | cia402::cw::change_immediately);
        if (setpoint_.new_setpoint_bit()) cw = static_cast<uint16_t>(cw | cia402::cw::new_setpoint);
    }
    if (halt_) cw = static_cast<uint16_t>(cw | cia402::cw::halt);
    const auto word = std::make_pair(setpoint_.target(), cw);
    if (!force && sent_rpdo1_ && *sent_rpdo1_ == word) return;
    out_.push_back(pack_pdo(rpdo1_, node_, {static_cast<uint32_t>(word.first), word.second}));
    sent_rpdo1_ = word;
}

void Drive::on_tpdo1(uint16_t statusword, int32_t counts, int64_t now_us, int64_t utime)
{
    ++counters_.tpdo_received;
    const cia402::State state = cia402::state_from_statusword(statusword);
    if (state != last_state_ &&
        (state == cia402::State::fault || state == cia402::State::fault_reaction_active) &&
        last_state_ != cia402::State::fault_reaction_active) {
        ++counters_.faults;
        char buf[64];
        std::snprintf(buf, sizeof buf, "drive entered %s (last EMCY 0x%04X)", cia402::to_string(state), last_emcy_code_);
        event(DriveEvent::Level::warning, buf);
    }
    last_state_ = state;

    DriveSample s;
    s.utime = utime;
    s.counts = counts;
    s.angle_rad = config_.units.to_rad(counts);
    s.velocity_rad_s = velocity_rad_s_;
    s.statusword = statusword;
    s.state = state;
    s.target_rad = config_.units.to_rad(setpoint_.target());

    switch (phase_) {
    case Phase::starting:
        // The first position: hold it, so the enabled drive does not jump to a stale target.
        setpoint_.reset(counts);
        s.target_rad = s.angle_rad;
        enabler_.set_goal(true, now_us);
        phase_ = Phase::enabling;
        phase_us_ = now_us;
        [[fallthrough]];
    case Phase::enabling: {
        enabler_.on_statusword(statusword, now_us);
        if (enabler_.reached()) {
            phase_ = Phase::operational;
            event(DriveEvent::Level::info, "operation enabled");
        }
        send_rpdos(false);
        break;
    }
    case Phase::operational:
        if (state != cia402::State::operation_enabled) {
            // Fault or quick stop: hold where we are and walk back to Operation Enabled.
            setpoint_.reset(counts);
            enabler_.set_goal(true, now_us);
            enabler_.on_statusword(statusword, now_us);
            phase_ = Phase::enabling;
            send_rpdos(false);
            break;
        }
        if (setpoint_.on_statusword(statusword, now_us)) send_rpdos(false);
        break;
    case Phase::halting:
        if ((statusword & cia402::sw::target_reached) || now_us - phase_us_ > config_.halt_timeout_us ||
            state != cia402::State::operation_enabled) {
            enabler_.set_goal(false, now_us);
            phase_ = Phase::disabling;
            phase_us_ = now_us;
        }
        [[fallthrough]];
    case Phase::disabling:
        if (phase_ == Phase::disabling) {
            enabler_.on_statusword(statusword, now_us);
            if (enabler_.reached()) phase_ = Phase::stopped;
        }
        send_rpdos(false);
        break;
    default: break;
    }
    last_ = s;
    samples_.push_back(s);
}

void Drive::on_frame(const io::CanFrame& frame, int64_t now_us, int64_t utime, bool read_late)
{
    ++frames_since_start_;
    if (frame.extended || frame.rtr) return;
    if (sdo_.on_frame(frame, now_us, out_)) return;
    if (auto hb = decode_heartbeat(frame, node_)) {
        heartbeat_.on_frame(frame, now_us);
        if (*hb == NmtState::boot_up && phase_ != Phase::configuring && phase_ != Phase::idle &&
            phase_ != Phase::failed) {
            fail("node " + std::to_string(node_) + " rebooted (boot-up heartbeat)");
        }
        return;
    }
    if (auto emcy = decode_emcy(frame, node_)) {
        ++counters_.emcy;
        if (!emcy->is_reset()) last_emcy_code_ = emcy->error_code;
        char buf[96];
        std::snprintf(buf, sizeof buf, "EMCY 0x%04X (%s), error register 0x%02X", emcy->error_code,
                      describe_emcy(emcy->error_code), emcy->error_register);
        event(emcy->is_reset() ? DriveEvent::Level::info : DriveEvent::Level::warning, buf);
        return;
    }
    if (phase_ == Phase::idle || phase_ == Phase::failed || phase_ == Phase::configuring) return;
    if (auto v = unpack_pdo(tpdo2_, node_, frame)) {
        const double velocity = config_.units.to_rad_s(static_cast<double>(static_cast<int32_t>((*v)[0])));
        if (config_.check_tpdo_plausibility &&
            std::fabs(velocity) > 2.0 * config_.max_velocity_rad_s + kVelocitySlackRadS) {
            ++counters_.tpdo_implausible;
            return;
        }
        velocity_rad_s_ = velocity;
        return;
    }
    if (auto v = unpack_pdo(tpdo1_, node_, frame)) {
        // With SYNC the host's own SYNC times the sample: the receive time is kept.
        if (config_.sync_period_us == 0) {
            const int lost = std::exchange(lost_frames_, 0);
            utime = read_late ? tpdo1_clock_.update_read_late(utime, lost) : tpdo1_clock_.update(utime, lost);
            counters_.clock_restarts = tpdo1_clock_.restarts();
        }
        const auto statusword = static_cast<uint16_t>((*v)[0]);
        const auto counts = static_cast<int32_t>((*v)[1]);
        if (config_.check_tpdo_plausibility &&
            !plausible_tpdo1({cia402::state_from_statusword(statusword), counts, utime}))
            return;
        on_tpdo1(statusword, counts, now_us, utime);
    }
}

double Drive::max_step_rad(double dt_s) const
{
    const double period_s = config_.sync_period_us > 0 ? static_cast<double>(config_.sync_period_us) * 1e-6
                                                       : config_.tpdo_period_ms * 1e-3;
    return 2.0 * config_.max_velocity_rad_s * std::max(dt_s, period_s) + kPositionSlackRad;
}

bool Drive::readings_agree(const Tpdo1Reading& earlier, const Tpdo1Reading& later) const
{
    if (earlier.state != later.state) return false;
    const double dt_s = static_cast<double>(later.utime - earlier.utime) * 1e-6;
    return std::fabs(config_.units.to_rad(later.counts) - config_.units.to_rad(earlier.counts)) <= max_step_rad(dt_s);
}

bool Drive::plausible_tpdo1(const Tpdo1Reading& reading)
{
    const auto previous = std::exchange(last_tpdo1_reading_, reading);
    const bool previous_held = std::exchange(holding_tpdo1_, false);
    // Agrees with what was last taken: the one held before it (if any) was wrong.
    if (last_ && readings_agree({last_->state, last_->counts, last_->utime}, reading)) {
        if (previous_held) ++counters_.tpdo_implausible;
        return true;
    }
    // Agrees with the one before it: two in a row are a real change (a bit error does not
    // repeat itself), e.g. each step of the enable walk, a fault, the very first TPDO.
    if (previous && readings_agree(*previous, reading)) return true;
    if (previous_held) ++counters_.tpdo_implausible;
    holding_tpdo1_ = true;
    return false;
}

void Drive::tick(int64_t now_us)
{
    sdo_.tick(now_us, out_);
    switch (phase_) {
    case Phase::configuring:
        if (config_done_ && sdo_.idle()) {
            out_.push_back(encode_nmt(NmtCommand::start, node_));
            heartbeat_.reset(now_us);
            phase_ = Phase::starting;
            phase_us_ = now_us;
            next_sync_us_ = now_us;
        }
        break;
    case Phase::starting:
        if (now_us - phase_us_ > config_.start_timeout_us) fail("no TPDO1 within the start timeout after NMT start");
        break;
    case Phase::enabling:
    case Phase::disabling:
        if (enabler_.check_timeout(now_us)) send_rpdos(true);
        if (enabler_.failed()) {
            ++counters_.enable_failures;
            if (phase_ == Phase::disabling) {
                phase_ = Phase::stopped;
                event(DriveEvent::Level::warning, "disable did not complete; giving up");
            } else {
                fail(std::string("could not enable the drive: stuck in ") + cia402::to_string(enabler_.state()));
            }
        }
        break;
    case Phase::operational:
        if (setpoint_.poll(now_us)) send_rpdos(false);
        break;
    case Phase::halting:
        if (now_us - phase_us_ > config_.halt_timeout_us) {
            enabler_.set_goal(false, now_us);
            phase_ = Phase::disabling;
            phase_us_ = now_us;
            send_rpdos(true);
        }
        break;
    default: break;
    }
    const bool running = phase_ == Phase::starting || phase_ == Phase::enabling || phase_ == Phase::operational ||
                         phase_ == Phase::halting || phase_ == Phase::disabling;
    if (running && heartbeat_.check_lost(now_us)) {
        ++counters_.heartbeat_losses;
        fail("heartbeat of node " + std::to_string(node_) + " lost (3 periods without one)");
        return;
    }
    if (running && config_.sync_period_us > 0 && now_us >= next_sync_us_) {
        io::CanFrame sync;
        sync.id = kSyncId;
        out_.push_back(sync);
        next_sync_us_ += config_.sync_period_us;
        if (next_sync_us_ < now_us) next_sync_us_ = now_us + config_.sync_period_us;  // after a stall
    }
}

std::vector<io::CanFrame> Drive::take_outgoing() { return std::exchange(out_, {}); }
std::vector<DriveSample> Drive::take_samples() { return std::exchange(samples_, {}); }
std::vector<DriveEvent> Drive::take_events() { return std::exchange(events_, {}); }

DriveCounters Drive::counters() const
{
    DriveCounters c = counters_;
    c.sdo_timeouts = sdo_.timeouts();
    c.sdo_aborts = sdo_.aborts();
    c.fault_resets = enabler_.fault_resets() + counters_.fault_resets;
    c.setpoints_acknowledged = setpoint_.acknowledged();
    c.setpoint_timeouts = setpoint_.timeouts();
    return c;
}

}  // namespace ugv::canopen
