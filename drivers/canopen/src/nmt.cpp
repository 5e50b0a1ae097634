#include "ugv/canopen/nmt.hpp"

#include "ugv/canopen/ids.hpp"

namespace ugv::canopen {

io::CanFrame encode_nmt(NmtCommand command, uint8_t node)
{
    io::CanFrame f;
    f.id = kNmtId;
    f.dlc = 2;
    f.data[0] = static_cast<uint8_t>(command);
    f.data[1] = node;
    return f;
}

io::CanFrame encode_heartbeat(uint8_t node, NmtState state)
{
    io::CanFrame f;
    f.id = kHeartbeatBase + node;
    f.dlc = 1;
    f.data[0] = static_cast<uint8_t>(state);
    return f;
}

std::optional<NmtCommand> decode_nmt(const io::CanFrame& frame, uint8_t node)
{
    if (frame.id != kNmtId || frame.extended || frame.rtr || frame.dlc != 2) return std::nullopt;
    if (frame.data[1] != 0 && frame.data[1] != node) return std::nullopt;
    switch (frame.data[0]) {
    case 0x01: return NmtCommand::start;
    case 0x02: return NmtCommand::stop;
    case 0x80: return NmtCommand::enter_pre_operational;
    case 0x81: return NmtCommand::reset_node;
    case 0x82: return NmtCommand::reset_communication;
    default: return std::nullopt;
    }
}

std::optional<NmtState> decode_heartbeat(const io::CanFrame& frame, uint8_t node)
{
    if (frame.id != kHeartbeatBase + node || frame.extended || frame.rtr || frame.dlc < 1) return std::nullopt;
    // Bit 7 is the node-guarding toggle bit; a heartbeat sends it as 0, but mask it anyway.
    switch (frame.data[0] & 0x7F) {
    case 0x00: return NmtState::boot_up;
    case 0x04: return NmtState::stopped;
    case 0x05: return NmtState::operational;
    case 0x7F: return NmtState::pre_operational;
    default: return std::nullopt;
    }
}

const char* to_string(NmtState state)
{
    switch (state) {
    case NmtState::boot_up: return "boot-up";
    case NmtState::stopped: return "stopped";
    case NmtState::operational: return "operational";
    case NmtState::pre_operational: return "pre-operational";
    }
    return "?";
}

HeartbeatConsumer::HeartbeatConsumer(uint8_t node, int64_t period_us, int missed_beats)
    : node_(node), period_us_(period_us), missed_beats_(missed_beats)
{
}

void HeartbeatConsumer::reset(int64_t now_us)
{
    last_us_ = now_us;
    lost_ = false;
    last_state_.reset();
}

bool HeartbeatConsumer::on_frame(const io::CanFrame& frame, int64_t now_us)
{
    const auto state = decode_heartbeat(frame, node_);
    if (!state) return false;
    last_us_ = now_us;
    last_state_ = state;
    lost_ = false;
    return true;
}

bool HeartbeatConsumer::check_lost(int64_t now_us)
{
    if (lost_ || now_us - last_us_ <= timeout_us()) return false;
    lost_ = true;
    return true;
}

}  // namespace ugv::canopen
