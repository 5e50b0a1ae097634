// Any sequence of CAN frames into the CANopen decoders and a CiA 402 Drive session, as the
// servo daemon feeds them from the bus. The input is a list of 12-byte records:
//   [0] step: bits 0-5 = milliseconds to advance (then tick()), bit 6 = a set-point request
//       (the angle is the record's 8 data bytes as a double: NaN, Inf, huge included),
//       bit 7 = restart the session
//   [1..2] COB-ID (11 bits, big-endian), [3] bits 0-3 DLC (clamped to 8), bit 4 extended,
//       bit 5 RTR, [4..11] data
// Checks, beyond "no crash":
//  - every frame the session sends is a standard 11-bit frame with DLC <= 8;
//  - every target position it sends in an RPDO of its current plan is inside the configured
//    angle limits, or is an actual position the drive reported (the "hold where you are"
//    target), in a TPDO of the plan or an SDO upload of 0x6064;
//  - every sample's state is the state its statusword shows, and its angle is finite;
//  - a failed session says why;
//  - the stateless decoders: SDO sizes within 0..4 bytes and values that fit them, and
//    heartbeats only with a known NMT state.
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <set>
#include <vector>

#include "ugv/canopen/drive.hpp"
#include "ugv/canopen/emcy.hpp"
#include "ugv/canopen/ids.hpp"

namespace {

using namespace ugv::canopen;

void require(bool ok)
{
    if (!ok) std::abort();
}

bool fits(uint32_t value, int size) { return size >= 4 || value < (uint32_t{1} << (8 * size)); }

// The value of object `index` in a frame of one of pdos (the plan's), if it carries it.
std::optional<uint32_t> value_in(const std::vector<Plan::Pdo>& pdos, uint16_t index, uint8_t node,
                                 const ugv::io::CanFrame& f)
{
    for (const Plan::Pdo& p : pdos) {
        for (std::size_t k = 0; k < p.mapping.objects.size(); ++k) {
            if (p.mapping.objects[k].index != index) continue;
            if (auto v = unpack_pdo(p.mapping, node, f); v && k < v->size()) return (*v)[k];
        }
    }
    return std::nullopt;
}

void check_stateless(const ugv::io::CanFrame& f, uint8_t node)
{
    if (auto r = decode_sdo_response(f, node)) {
        require(r->size >= 0 && r->size <= 4);
        if (r->kind == SdoResponse::Kind::upload_data) require(r->size >= 1 && fits(r->value, r->size));
    }
    if (auto q = decode_sdo_request(f, node)) {
        require(q->size >= 0 && q->size <= 4);
        if (q->kind == SdoRequest::Kind::download && q->size > 0) require(fits(q->value, q->size));
    }
    if (auto hb = decode_heartbeat(f, node)) {
        const auto s = *hb;
        require(s == NmtState::boot_up || s == NmtState::stopped || s == NmtState::operational ||
                s == NmtState::pre_operational);
    }
    (void)decode_nmt(f, node);
    if (auto e = decode_emcy(f, node)) (void)describe_emcy(e->error_code);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    constexpr std::size_t kRecord = 12;
    DriveConfig config;
    config.node_id = 5;
    Drive drive(config);
    const int32_t lowest = config.units.to_counts(config.min_angle_rad);
    const int32_t highest = config.units.to_counts(config.max_angle_rad);
    std::set<int32_t> reported_positions;

    int64_t now_us = 1'000'000;
    drive.start(now_us);
    for (std::size_t at = 0; at + kRecord <= size; at += kRecord) {
        const uint8_t* r = data + at;
        if (r[0] & 0x80) drive.start(now_us);
        ugv::io::CanFrame f;
        f.id = static_cast<uint32_t>((r[1] << 8 | r[2]) & 0x7FF);
        f.dlc = static_cast<uint8_t>(std::min(r[3] & 0x0F, 8));
        f.extended = (r[3] & 0x10) != 0;
        f.rtr = (r[3] & 0x20) != 0;
        std::memcpy(f.data.data(), r + 4, 8);
        check_stateless(f, config.node_id);
        if (!f.extended && !f.rtr) {
            if (auto v = value_in(drive.plan().tpdos, cia402::kPositionActual, config.node_id, f))
                reported_positions.insert(static_cast<int32_t>(*v));
            if (auto r = decode_sdo_response(f, config.node_id);
                r && r->kind == SdoResponse::Kind::upload_data && r->at.index == cia402::kPositionActual)
                reported_positions.insert(static_cast<int32_t>(r->value));
        }
        drive.on_frame(f, now_us, now_us);
        if (r[0] & 0x40) {
            double angle = 0;
            std::memcpy(&angle, r + 4, sizeof angle);
            drive.command(angle, 1.0);
        }
        now_us += 1000 * (r[0] & 0x3F);
        drive.tick(now_us);

        for (const auto& out : drive.take_outgoing()) {
            require(!out.extended && out.id <= 0x7FF && out.dlc <= 8);
            if (auto v = value_in(drive.plan().rpdos, cia402::kTargetPosition, config.node_id, out)) {
                const auto target = static_cast<int32_t>(*v);
                require((target >= lowest && target <= highest) || reported_positions.count(target) == 1);
            }
        }
        for (const auto& s : drive.take_samples()) {
            require(s.state == cia402::state_from_statusword(s.statusword));
            require(std::isfinite(s.angle_rad) && std::isfinite(s.velocity_rad_s) && std::isfinite(s.target_rad));
        }
        (void)drive.take_events();
        if (drive.phase() == Drive::Phase::failed) require(!drive.failure().empty());
    }
    return 0;
}
