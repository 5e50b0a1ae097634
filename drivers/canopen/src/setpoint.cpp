#include "ugv/canopen/setpoint.hpp"

#include "ugv/canopen/cia402.hpp"

namespace ugv::canopen::cia402 {

void SetpointHandshake::request(int32_t target_counts, uint32_t velocity_counts_s)
{
    queued_ = std::make_pair(target_counts, velocity_counts_s);
}

void SetpointHandshake::reset(int32_t hold_counts)
{
    phase_ = Phase::idle;
    queued_.reset();
    target_ = hold_counts;
}

bool SetpointHandshake::on_statusword(uint16_t statusword, int64_t now_us)
{
    const bool ack = (statusword & sw::setpoint_acknowledge) != 0;
    if (phase_ == Phase::raised && ack) {
        ++acknowledged_;
        phase_ = Phase::lowered;
        phase_us_ = now_us;
        return true;
    }
    if (phase_ == Phase::lowered && !ack) {
        phase_ = Phase::idle;
        return poll(now_us);
    }
    return false;
}

bool SetpointHandshake::poll(int64_t now_us)
{
    if (phase_ != Phase::idle && now_us - phase_us_ > timeout_us_) {
        // No acknowledge (or it never fell): lower bit 4 and start over with the newest target.
        ++timeouts_;
        phase_ = Phase::idle;
        if (!queued_) queued_ = std::make_pair(target_, velocity_);
        return true;
    }
    if (phase_ == Phase::idle && queued_) {
        target_ = queued_->first;
        velocity_ = queued_->second;
        queued_.reset();
        phase_ = Phase::raised;
        phase_us_ = now_us;
        return true;
    }
    return false;
}

}  // namespace ugv::canopen::cia402
