// The profile-position set-point handshake (CiA 402): write the target (0x607A), raise
// controlword bit 4 (new set-point), wait for statusword bit 12 (set-point acknowledge),
// lower bit 4, wait for bit 12 to fall. Only then may the next set-point go. A request that
// arrives while a handshake runs is kept (the newest wins) and sent next.
#pragma once

#include <cstdint>
#include <optional>
#include <utility>

namespace ugv::canopen::cia402 {

class SetpointHandshake
{
public:
    explicit SetpointHandshake(int64_t timeout_us = 200'000) : timeout_us_(timeout_us) {}

    // Queues a target (drive counts) with its profile velocity (counts/s).
    void request(int32_t target_counts, uint32_t velocity_counts_s);
    // Forgets everything (re-initialisation, fault): the next request starts fresh.
    void reset(int32_t hold_counts);

    // Feed each statusword; returns true when target()/new_setpoint_bit() changed and the
    // caller must send them (RPDO).
    bool on_statusword(uint16_t statusword, int64_t now_us);
    // Starts a queued request when idle, and abandons a handshake that timed out. True when
    // the caller must send.
    bool poll(int64_t now_us);

    int32_t target() const { return target_; }
    uint32_t velocity() const { return velocity_; }
    bool new_setpoint_bit() const { return phase_ == Phase::raised; }
    bool busy() const { return phase_ != Phase::idle; }
    uint64_t acknowledged() const { return acknowledged_; }
    uint64_t timeouts() const { return timeouts_; }

private:
    enum class Phase { idle, raised, lowered };
    Phase phase_ = Phase::idle;
    int64_t timeout_us_;
    int64_t phase_us_ = 0;
    int32_t target_ = 0;
    uint32_t velocity_ = 0;
    std::optional<std::pair<int32_t, uint32_t>> queued_;
    uint64_t acknowledged_ = 0;
    uint64_t timeouts_ = 0;
};

}  // namespace ugv::canopen::cia402
