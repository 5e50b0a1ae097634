// NMT (network management) commands, heartbeat states and the heartbeat consumer.
#pragma once

#include <cstdint>
#include <optional>

#include "ugv/io/can_frame.hpp"

namespace ugv::canopen {

enum class NmtCommand : uint8_t {
    start = 0x01,
    stop = 0x02,
    enter_pre_operational = 0x80,
    reset_node = 0x81,
    reset_communication = 0x82,
};

// The state byte a node sends in its heartbeat (0x700 + id).
enum class NmtState : uint8_t {
    boot_up = 0x00,
    stopped = 0x04,
    operational = 0x05,
    pre_operational = 0x7F,
};

// `[cmd, node]` on COB-ID 0; node 0 addresses every node.
io::CanFrame encode_nmt(NmtCommand command, uint8_t node);
// The heartbeat frame a node with this id sends in this state.
io::CanFrame encode_heartbeat(uint8_t node, NmtState state);
// The NMT command in a frame on COB-ID 0 addressed to node (or to all); nullopt otherwise.
std::optional<NmtCommand> decode_nmt(const io::CanFrame& frame, uint8_t node);
// The state in a heartbeat from node; nullopt for any other frame or an unknown state byte.
std::optional<NmtState> decode_heartbeat(const io::CanFrame& frame, uint8_t node);

const char* to_string(NmtState state);

// Watches one producer's heartbeat. The node is lost when no heartbeat arrived for
// missed_beats (3 by default) producer periods; lost() reports the transition once.
class HeartbeatConsumer
{
public:
    HeartbeatConsumer(uint8_t node, int64_t period_us, int missed_beats = 3);

    // Arms the watch from now (the first heartbeat is due within the same window).
    void reset(int64_t now_us);
    // True when the frame was this node's heartbeat.
    bool on_frame(const io::CanFrame& frame, int64_t now_us);
    // True exactly once, at the first check after the window expired without a heartbeat.
    bool check_lost(int64_t now_us);

    bool alive() const { return !lost_; }
    std::optional<NmtState> last_state() const { return last_state_; }
    int64_t timeout_us() const { return period_us_ * missed_beats_; }

private:
    uint8_t node_;
    int64_t period_us_;
    int missed_beats_;
    int64_t last_us_ = 0;
    bool lost_ = false;
    std::optional<NmtState> last_state_;
};

}  // namespace ugv::canopen
