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
// The probe's reads and the configuration's writes may be repeated at will: two more tries
// each, so that a noisy line (an slcan reply lost to a bit error) does not fail a start-up
// of ~80 transfers.
constexpr int kProbeExtraRetries = 2;

std::string hex_address(SdoAddress at)
{
    char buf[16];
    std::snprintf(buf, sizeof buf, "0x%04X:%02X", at.index, at.subindex);
    return buf;
}

}  // namespace

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
    case Phase::probed: return "probed";
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
      plausibility_(0.0, 0.0)
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

void Drive::start(int64_t now_us, bool probe_only)
{
    sdo_.clear();
    failure_.clear();
    mandatory_missing_ = false;
    config_done_ = false;
    halt_ = false;
    probe_only_ = probe_only;
    replans_in_session_ = 0;
    sent_rpdo1_.reset();
    sent_velocity_.reset();
    sent_target_sdo_.reset();
    sent_cw_sdo_.reset();
    last_state_ = cia402::State::unknown;
    last_.reset();
    latest_statusword_ = 0;
    lost_frames_ = 0;
    frames_since_start_ = 0;
    counters_.fault_resets += enabler_.fault_resets();  // the fresh enabler counts from 0
    enabler_ = cia402::Enabler(config_.enabler);
    phase_ = Phase::configuring;
    phase_us_ = now_us;
    // PDOs must not run while their mapping is rewritten.
    out_.push_back(encode_nmt(NmtCommand::enter_pre_operational, node_));
    queue_probe();
    event(DriveEvent::Level::info, (probe_only ? "probing node " : "configuring node ") + std::to_string(node_));
}

namespace {
bool absent(const SdoResult& r)
{
    return !r.ok && !r.timed_out && (r.abort_code == abort_code::no_object || r.abort_code == abort_code::no_subindex);
}
}  // namespace

void Drive::queue_probe()
{
    probing_ = true;
    probe_error_.clear();
    caps_ = DriveCapabilities{};
    caps_.heartbeat_producer = false;
    for (int n = 1; n <= 4; ++n) {
        PdoResource t;
        t.number = n;
        t.transmit = true;
        caps_.tpdos.push_back(t);
        t.transmit = false;
        caps_.rpdos.push_back(t);
    }
    auto timed_out = [this](SdoAddress at, const SdoResult& r) { return probe_timed_out("SDO read ", at, r); };
    // The daemon reads only what the plan needs (each transfer is one more chance for a noisy
    // line to time it out); mapping rights and object limits it learns from the aborts of its
    // configuration writes. --probe reads them all, and the identity.
    for (uint8_t sub = 1; sub <= (probe_only_ ? 4 : 0); ++sub)
        sdo_.read({0x1018, sub}, [this, sub, timed_out](const SdoResult& r) {
            if (timed_out({0x1018, sub}, r) || !r.ok) return;
            caps_.identity.present = true;
            uint32_t* field[] = {&caps_.identity.vendor_id, &caps_.identity.product_code, &caps_.identity.revision,
                                 &caps_.identity.serial};
            *field[sub - 1] = r.value;
        }, kProbeExtraRetries);
    sdo_.read({cia402::kSupportedModes, 0}, [this, timed_out](const SdoResult& r) {
        if (timed_out({cia402::kSupportedModes, 0}, r)) return;
        if (r.ok) caps_.supported_modes = r.value;
    }, kProbeExtraRetries);
    for (uint16_t index : {cia402::kStatusword, cia402::kControlword, cia402::kPositionActual, cia402::kTargetPosition,
                           cia402::kModesOfOperation, cia402::kModesDisplay, cia402::kVelocityActual,
                           cia402::kProfileVelocity, cia402::kProfileAcceleration, cia402::kProfileDeceleration})
        sdo_.read({index, 0}, [this, index, timed_out](const SdoResult& r) {
            if (timed_out({index, 0}, r)) return;
            if (!absent(r)) caps_.objects.insert(index);  // a write-only object aborts, but exists
        }, kProbeExtraRetries);
    sdo_.read({cia402::kHeartbeatProducerTime, 0}, [this, timed_out](const SdoResult& r) {
        if (!timed_out({cia402::kHeartbeatProducerTime, 0}, r)) caps_.heartbeat_producer = !absent(r);
    }, kProbeExtraRetries);
    if (probe_only_)
        sdo_.read({0x100C, 0}, [this, timed_out](const SdoResult& r) {
            if (!timed_out({0x100C, 0}, r)) caps_.node_guarding = !absent(r);
        }, kProbeExtraRetries);
    probe_pdo(caps_.tpdos[0]);
    probe_pdo(caps_.rpdos[0]);
}

bool Drive::probe_timed_out(const char* what, SdoAddress at, const SdoResult& r)
{
    // A timeout ends the probe (the drive is not there); an abort is an answer.
    if (!r.timed_out) return false;
    if (probe_error_.empty()) fail(what + hex_address(at) + " timed out");
    probe_error_ = "timeout";
    return true;
}

void Drive::probe_pdo(PdoResource& res)
{
    PdoResource* r = &res;  // caps_ is not resized until the next probe
    const auto comm = static_cast<uint16_t>((r->transmit ? 0x1800 : 0x1400) + r->number - 1);
    const auto map = static_cast<uint16_t>((r->transmit ? 0x1A00 : 0x1600) + r->number - 1);
    sdo_.read({comm, 1}, [this, r, comm, map](const SdoResult& c) {
        if (probe_timed_out("SDO read ", {comm, 1}, c) || !c.ok) return;  // 0x06020000: the drive has no such PDO (nor, we take it, the next)
        r->present = true;
        r->cob_id = c.value;
        if (r->number < 4) {
            auto& list = r->transmit ? caps_.tpdos : caps_.rpdos;
            probe_pdo(list[static_cast<std::size_t>(r->number)]);
        }
        if (r->transmit)
            sdo_.read({comm, 5}, [this, r, comm](const SdoResult& e) {
                if (!probe_timed_out("SDO read ", {comm, 5}, e)) r->event_timer = e.ok || !absent(e);
            });
        sdo_.read({map, 0}, [this, r, comm, map](const SdoResult& m) {
            if (probe_timed_out("SDO read ", {map, 0}, m)) return;
            if (!m.ok) {
                r->remappable = false;
                r->refused_code = m.abort_code;
                return;
            }
            const uint32_t count = std::min<uint32_t>(m.value & 0xFF, 8);
            if (count > 0 || probe_only_) probe_mapping_entry(r, map, count, 1);
            if (!probe_only_) return;
            // Mapping rights: disable the PDO, write its own count back, restore the COB-ID.
            // Nothing changes on a drive that accepts; a fixed mapping aborts (0x06010002).
            const uint32_t cob = r->cob_id;
            sdo_.write({comm, 1}, cob | 0x80000000u, 4, [this, r, comm, map, cob, count](const SdoResult& d) {
                if (probe_timed_out("SDO write ", {comm, 1}, d)) return;
                if (!d.ok) {
                    r->remappable = false;
                    r->refused_code = d.abort_code;
                    return;
                }
                sdo_.write({map, 0}, count, 1, [this, r, map](const SdoResult& w) {
                    if (probe_timed_out("SDO write ", {map, 0}, w) || w.ok) return;
                    r->remappable = false;
                    r->refused_code = w.abort_code;
                });
                sdo_.write({comm, 1}, cob, 4);
            });
        });
    }, kProbeExtraRetries);
}

void Drive::probe_mapping_entry(PdoResource* r, uint16_t map, uint32_t count, uint8_t sub)
{
    // The entries in use, then how many sub-indices the mapping has at all (its object limit).
    sdo_.read({map, sub}, [this, r, map, count, sub](const SdoResult& e) {
        if (probe_timed_out("SDO read ", {map, sub}, e)) return;
        if (!e.ok) {
            r->max_objects = sub - 1;
            return;
        }
        if (sub <= count)
            r->default_mapping.push_back({static_cast<uint16_t>(e.value >> 16), static_cast<uint8_t>((e.value >> 8) & 0xFF),
                                          static_cast<uint8_t>(e.value & 0xFF)});
        // The entries in use; --probe goes on to find how many the PDO has (its object limit).
        if (sub < (probe_only_ ? 8u : count)) probe_mapping_entry(r, map, count, static_cast<uint8_t>(sub + 1));
    }, kProbeExtraRetries);
}

void Drive::make_plan()
{
    PlanOptions o;
    o.tpdo_period_ms = config_.tpdo_period_ms;
    o.sync_period_us = config_.sync_period_us;
    o.sync_only_period_us = int64_t{config_.tpdo_period_ms} * 1000;
    plan_ = plan_bring_up(caps_, o);
    counters_.plan = plan_.flags;
    plausibility_dropped_ += plausibility_.dropped();
    plausibility_ = TpdoPlausibility(config_.max_velocity_rad_s * static_cast<double>(drive_period_us()) * 1e-6,
                                     kPositionSlackRad);
    tpdo1_clock_ = io::PeriodicClock(static_cast<double>(drive_period_us()) * 1e-6, 1, tpdo1_clock_.restarts());
}

void Drive::queue_configuration()
{
    sdo_.clear();
    if (plan_.check_supported_modes && caps_.supported_modes && (*caps_.supported_modes & 0x1u) == 0) {
        fail("drive does not support profile position mode (0x6502 = " + std::to_string(*caps_.supported_modes) + ")");
        return;
    }
    std::vector<SdoWrite> writes;
    if (plan_.use_heartbeat)
        writes.push_back({{cia402::kHeartbeatProducerTime, 0}, static_cast<uint32_t>(config_.heartbeat_period_ms), 2});
    for (const auto* list : {&plan_.tpdos, &plan_.rpdos})
        for (const auto& p : *list) {
            const auto w = pdo_configuration(p.mapping, node_, p.write_mapping);
            writes.insert(writes.end(), w.begin(), w.end());
        }
    writes.push_back({{cia402::kModesOfOperation, 0}, static_cast<uint32_t>(cia402::kModeProfilePosition), 1});
    if (plan_.write_acceleration) {
        const uint32_t accel = std::max<uint32_t>(1, config_.units.to_counts_rate(config_.acceleration_rad_s2));
        writes.push_back({{cia402::kProfileAcceleration, 0}, accel, 4});
        writes.push_back({{cia402::kProfileDeceleration, 0}, accel, 4});
    }
    for (const auto& w : writes) {
        // Writing a configuration value again changes nothing: as many tries as the probe's.
        sdo_.write(
            w.at, w.value, w.size, [this, w](const SdoResult& r) {
                if (!r.ok) on_config_refused(w, r);
            },
            kProbeExtraRetries);
    }
    // Mode display must confirm profile position before the drive is enabled.
    const uint16_t display = caps_.has(cia402::kModesDisplay) ? cia402::kModesDisplay : cia402::kModesOfOperation;
    sdo_.read(
        {display, 0}, [this, display](const SdoResult& r) {
        if (!r.ok) {
            fail("SDO read " + hex_address({display, 0}) + " " +
                 (r.timed_out ? "timed out" : "aborted: " + describe_abort(r.abort_code)));
            return;
        }
        if (static_cast<int8_t>(r.value & 0xFF) != cia402::kModeProfilePosition) {
            fail("drive did not take profile position mode (" + hex_address({display, 0}) + " = " +
                 std::to_string(static_cast<int8_t>(r.value & 0xFF)) + ")");
            return;
        }
        config_done_ = true;
        },
        kProbeExtraRetries);
}

PdoResource* Drive::resource_of(uint16_t index)
{
    const int base = index & 0xFF00;
    const int n = (index & 0xFF) + 1;
    if (n < 1 || n > 4) return nullptr;
    auto& list = (base == 0x1800 || base == 0x1A00) ? caps_.tpdos : caps_.rpdos;
    if (base != 0x1400 && base != 0x1600 && base != 0x1800 && base != 0x1A00) return nullptr;
    return &list[static_cast<std::size_t>(n - 1)];
}

void Drive::on_config_refused(const SdoWrite& w, const SdoResult& r)
{
    const std::string what = "SDO write " + hex_address(w.at) +
                             (r.timed_out ? " timed out" : " aborted: " + describe_abort(r.abort_code));
    PdoResource* res = r.timed_out ? nullptr : resource_of(w.at.index);
    if (!res) {
        fail(what);
        return;
    }
    const bool mapping = (w.at.index & 0x0200) != 0;  // 0x1600/0x1A00
    const uint32_t code = r.abort_code;
    bool learnt = true;
    if (mapping && w.at.subindex != 0 && code == abort_code::not_mappable && caps_.unmappable.count(w.value) == 0) {
        caps_.unmappable.insert(w.value);
    } else if (mapping && (code == abort_code::mapping_too_long || code == abort_code::no_subindex) &&
               res->max_objects > 1) {
        const int tried = w.at.subindex == 0 ? static_cast<int>(w.value) : w.at.subindex;
        res->max_objects = std::min(res->max_objects, tried - 1);
        if (res->max_objects < 1) res->remappable = false;
    } else if (res->remappable && (code == abort_code::read_only || code == abort_code::unsupported_access ||
                                   code == abort_code::no_object || code == abort_code::not_mappable ||
                                   code == abort_code::mapping_too_long || code == abort_code::no_subindex)) {
        res->remappable = false;
        res->refused_code = code;
    } else if (!mapping && res->transmit && (w.at.subindex == 2 || w.at.subindex == 5) && res->event_timer &&
               (code == abort_code::value_range || code == abort_code::no_subindex)) {
        res->event_timer = false;  // event transmission refused: SYNC only
    } else {
        learnt = false;
    }
    if (!learnt || ++replans_in_session_ > 16) {
        fail(what);
        return;
    }
    ++counters_.replans;
    event(DriveEvent::Level::warning, what + "; planning again with what the drive refused");
    make_plan();
    if (!plan_.ok()) {
        fail(plan_.fatal);
        return;
    }
    for (const auto& n : plan_.notes) event(DriveEvent::Level::warning, "degraded: " + n);
    queue_configuration();
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

uint32_t Drive::rpdo_value(uint16_t index, uint16_t cw) const
{
    switch (index) {
    case cia402::kControlword: return cw;
    case cia402::kTargetPosition: return static_cast<uint32_t>(setpoint_.target());
    case cia402::kProfileVelocity: return setpoint_.velocity();
    case cia402::kModesOfOperation: return static_cast<uint8_t>(cia402::kModeProfilePosition);
    case cia402::kProfileAcceleration:
    case cia402::kProfileDeceleration:
        return std::max<uint32_t>(1, config_.units.to_counts_rate(config_.acceleration_rad_s2));
    default: return 0;
    }
}

void Drive::sdo_write_runtime(uint16_t index, uint32_t value, int size)
{
    sdo_.write({index, 0}, value, size, [this, index](const SdoResult& r) {
        if (r.ok) return;
        fail("SDO write " + hex_address({index, 0}) +
             (r.timed_out ? " timed out" : " aborted: " + describe_abort(r.abort_code)));
    });
}

void Drive::send_rpdos(bool force)
{
    uint16_t cw = enabler_.command();
    if (phase_ == Phase::operational || phase_ == Phase::halting) {
        cw = static_cast<uint16_t>(cw | cia402::cw::change_immediately);
        if (setpoint_.new_setpoint_bit()) cw = static_cast<uint16_t>(cw | cia402::cw::new_setpoint);
    }
    if (halt_) cw = static_cast<uint16_t>(cw | cia402::cw::halt);
    auto has = [](const Plan::Pdo& p, uint16_t index) {
        return std::any_of(p.mapping.objects.begin(), p.mapping.objects.end(),
                           [&](const MappedObject& o) { return o.index == index; });
    };
    auto pack = [&](const Plan::Pdo& p) {
        std::vector<uint32_t> values;
        for (const auto& o : p.mapping.objects) values.push_back(rpdo_value(o.index, cw));
        out_.push_back(pack_pdo(p.mapping, node_, values));
    };
    if (!sent_velocity_ || *sent_velocity_ != setpoint_.velocity()) {
        if (plan_.profile_velocity_by_sdo) sdo_write_runtime(cia402::kProfileVelocity, setpoint_.velocity(), 4);
        for (const auto& p : plan_.rpdos)
            if (has(p, cia402::kProfileVelocity) && !has(p, cia402::kControlword)) pack(p);
        sent_velocity_ = setpoint_.velocity();
    }
    const auto word = std::make_pair(setpoint_.target(), cw);
    if (!force && sent_rpdo1_ && *sent_rpdo1_ == word) return;
    sent_rpdo1_ = word;
    // Target before controlword: the drive must hold 0x607A before it sees the new-set-point
    // edge (both in one RPDO, target first, or in two, or by SDO in that order).
    if (plan_.target_by_sdo && (force || sent_target_sdo_ != word.first)) {
        sdo_write_runtime(cia402::kTargetPosition, static_cast<uint32_t>(word.first), 4);
        sent_target_sdo_ = word.first;
    }
    for (const auto& p : plan_.rpdos)
        if (has(p, cia402::kTargetPosition) && !has(p, cia402::kControlword)) pack(p);
    for (const auto& p : plan_.rpdos)
        if (has(p, cia402::kControlword)) pack(p);
    if (plan_.controlword_by_sdo && (force || sent_cw_sdo_ != cw)) {
        sdo_write_runtime(cia402::kControlword, cw, 2);
        sent_cw_sdo_ = cw;
    }
}

void Drive::on_tpdo1(uint16_t statusword, int32_t counts, int64_t now_us, int64_t utime)
{
    const cia402::State state = cia402::state_from_statusword(statusword);
    if (!plan_.velocity_from_tpdo && last_ && utime > last_->utime) {
        // No TPDO for 0x606C: the velocity between the last two positions taken.
        velocity_rad_s_ = (config_.units.to_rad(counts) - config_.units.to_rad(last_->counts)) /
                          (static_cast<double>(utime - last_->utime) * 1e-6);
    }
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
    if (phase_ == Phase::idle || phase_ == Phase::failed || phase_ == Phase::configuring || phase_ == Phase::probed)
        return;
    for (const auto& t : plan_.tpdos) {
        const auto v = unpack_pdo(t.mapping, node_, frame);
        if (!v) continue;
        last_tpdo_us_ = now_us;
        std::optional<uint16_t> statusword;
        std::optional<int32_t> counts;
        for (std::size_t i = 0; i < t.mapping.objects.size(); ++i) {
            const uint32_t x = (*v)[i];
            switch (t.mapping.objects[i].index) {
            case cia402::kStatusword: statusword = static_cast<uint16_t>(x); break;
            case cia402::kPositionActual: counts = static_cast<int32_t>(x); break;
            case cia402::kVelocityActual: {
                const double velocity = config_.units.to_rad_s(static_cast<double>(static_cast<int32_t>(x)));
                if (config_.check_tpdo_plausibility &&
                    std::fabs(velocity) > 2.0 * config_.max_velocity_rad_s + kVelocitySlackRadS) {
                    ++counters_.tpdo_implausible;
                    return;
                }
                velocity_rad_s_ = velocity;
                break;
            }
            default: break;
            }
        }
        if (!counts) {
            // Statusword in a TPDO of its own (split_status): taken with the next position.
            if (statusword) latest_statusword_ = *statusword;
            return;
        }
        const uint16_t sw = statusword.value_or(latest_statusword_);
        ++counters_.tpdo_received;
        // With SYNC the host's own SYNC times the sample: the receive time is kept.
        if (!plan_.produce_sync) {
            const int lost = std::exchange(lost_frames_, 0);
            utime = read_late ? tpdo1_clock_.update_read_late(utime, lost) : tpdo1_clock_.update(utime, lost);
            counters_.clock_restarts = tpdo1_clock_.restarts();
        }
        if (config_.check_tpdo_plausibility &&
            !plausibility_.check({cia402::state_from_statusword(sw), config_.units.to_rad(*counts)}))
            return;
        on_tpdo1(sw, *counts, now_us, utime);
        return;
    }
}

int64_t Drive::drive_period_us() const
{
    if (config_.sync_period_us > 0) return config_.sync_period_us;
    return int64_t{config_.tpdo_period_ms} * 1000;
}

void Drive::tick(int64_t now_us)
{
    sdo_.tick(now_us, out_);
    switch (phase_) {
    case Phase::configuring:
        if (probing_ && sdo_.idle()) {
            probing_ = false;
            make_plan();
            if (probe_only_) {
                phase_ = Phase::probed;
                break;
            }
            if (!plan_.ok()) {
                mandatory_missing_ = plan_.fatal.rfind("the drive lacks mandatory", 0) == 0;
                counters_.mandatory_missing = mandatory_missing_ ? 1 : 0;
                fail(plan_.fatal);
                break;
            }
            counters_.mandatory_missing = 0;
            for (const auto& n : plan_.notes) event(DriveEvent::Level::warning, "degraded: " + n);
            queue_configuration();
            break;
        }
        if (config_done_ && sdo_.idle()) {
            out_.push_back(encode_nmt(NmtCommand::start, node_));
            heartbeat_.reset(now_us);
            last_tpdo_us_ = now_us;
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
    if (running && plan_.use_heartbeat && heartbeat_.check_lost(now_us)) {
        ++counters_.heartbeat_losses;
        fail("heartbeat of node " + std::to_string(node_) + " lost (3 periods without one)");
        return;
    }
    // Without 0x1017 the TPDO stream is the life sign, over the same 3 heartbeat periods.
    if (running && !plan_.use_heartbeat && phase_ != Phase::starting &&
        now_us - last_tpdo_us_ > 3 * int64_t{config_.heartbeat_period_ms} * 1000) {
        ++counters_.heartbeat_losses;
        fail("node " + std::to_string(node_) + " silent: no TPDO for " + std::to_string(3 * config_.heartbeat_period_ms) +
             " ms (no heartbeat producer: supervised by its TPDO stream)");
        return;
    }
    // Up to 1 ms early: the caller's tick (one per period) may come a little early (the
    // daemon's timers by up to 0.5 ms), and waiting for the next would drop a SYNC period.
    if (running && plan_.produce_sync && now_us + std::min<int64_t>(1000, drive_period_us() / 4) >= next_sync_us_) {
        io::CanFrame sync;
        sync.id = kSyncId;
        out_.push_back(sync);
        next_sync_us_ += drive_period_us();
        if (next_sync_us_ < now_us) next_sync_us_ = now_us + drive_period_us();  // after a stall
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
    c.tpdo_implausible += plausibility_dropped_ + plausibility_.dropped();
    return c;
}

}  // namespace ugv::canopen
