// An emulated CiA 402 servo drive on a CAN bus, without I/O: frames in, frames out, and a
// clock the caller advances. It has NMT (boot-up, pre-operational, operational, stopped,
// resets), a heartbeat producer (0x1017), an expedited SDO server over its object dictionary
// (with CiA 301 aborts), configurable TPDOs (event timer or every n-th SYNC) and RPDOs, the
// CiA 402 state machine, profile position mode with the set-point handshake and the halt
// bit, and a position loop with velocity and acceleration limits and an integer encoder.
// Faults (with EMCY) and a heartbeat loss (the node drops off the bus) happen on request.
// The rest of the servo emulator's model: SlcanAdapter (slcan_adapter.hpp, bus <-> serial
// line) and SerialLineFaults; servo_command.cpp puts them on a pty.
#pragma once

#include <cstdint>
#include <vector>

#include "object_dictionary.hpp"
#include "ugv/canopen/cia402.hpp"
#include "ugv/canopen/nmt.hpp"
#include "ugv/io/can_frame.hpp"

namespace ugv::sim::servo {

struct DriveModel
{
    uint8_t node_id = 1;
    double max_velocity_counts_s = 200'000.0;       // motor limit, caps 0x6081
    double max_acceleration_counts_s2 = 2'000'000.0; // caps 0x6083/0x6084
    double initial_position_counts = 0.0;
    int64_t self_test_us = 50'000;          // not ready to switch on -> switch on disabled
    int64_t fault_reaction_us = 50'000;     // fault reaction active -> fault
    double target_window_counts = 2.0;      // target reached when this close and (almost) still
    DriveShape shape;                       // PDO resources, fixed mappings, heartbeat, SYNC only
};

class DriveEmulator
{
public:
    explicit DriveEmulator(DriveModel model);

    // Power-on at now_us: boot-up heartbeat, pre-operational.
    void power_on(int64_t now_us);
    void on_frame(const io::CanFrame& frame, int64_t now_us);
    // Runs the position loop and the timers up to now_us.
    void advance(int64_t now_us);
    std::vector<io::CanFrame> take_outgoing();

    // Faults and failures on request.
    void raise_fault(uint16_t error_code, int64_t now_us);
    // The node neither sends nor receives for duration_us (a loose connector).
    void drop_off_bus(int64_t duration_us, int64_t now_us);

    canopen::cia402::State state() const { return state_; }
    canopen::NmtState nmt_state() const { return nmt_; }
    double position_counts() const { return position_; }
    double velocity_counts_s() const { return velocity_; }
    int32_t target_counts() const { return static_cast<int32_t>(od_.get(0x607A, 0)); }
    uint16_t statusword() const { return statusword_; }
    uint64_t setpoints_accepted() const { return setpoints_accepted_; }
    const ObjectDictionary& dictionary() const { return od_; }

private:
    void send(const io::CanFrame& f);
    void on_sdo(const io::CanFrame& f);
    uint32_t check_write(uint16_t index, uint8_t sub, uint32_t value, int size) const;
    void apply_write(uint16_t index, uint8_t sub, uint32_t value);
    void on_rpdo(int n, const io::CanFrame& f);
    void on_sync();
    void on_controlword(uint16_t cw, int64_t now_us);
    void send_tpdo(int n);
    void update_statusword();
    void step_motion(double dt_s);
    void reboot(bool communication_only, int64_t now_us);

    DriveModel model_;
    uint8_t node_;
    ObjectDictionary od_;
    canopen::NmtState nmt_ = canopen::NmtState::boot_up;
    canopen::cia402::State state_ = canopen::cia402::State::not_ready_to_switch_on;
    uint16_t controlword_ = 0;
    uint16_t statusword_ = 0;
    int64_t now_us_ = 0;
    int64_t state_since_us_ = 0;
    // The next due time of a periodic timer: the last due time plus the period (a drive's
    // timers keep their cadence; counting from the moment the loop noticed would make the rate
    // sag by the poll latency), or now plus the period after a stall longer than a period.
    int64_t next_period(int64_t due_us, int64_t period_us) const
    {
        const int64_t next = due_us + period_us;
        return next > now_us_ ? next : now_us_ + period_us;
    }
    int64_t next_heartbeat_us_ = 0;
    int64_t tpdo_next_us_[4] = {0, 0, 0, 0};
    int sync_count_[4] = {0, 0, 0, 0};
    int64_t off_bus_until_us_ = 0;
    bool powered_ = false;

    // Motion (counts, counts/s).
    double position_ = 0.0;
    double velocity_ = 0.0;
    double move_target_ = 0.0;
    bool setpoint_ack_ = false;
    bool moving_ = false;
    uint16_t error_code_ = 0;
    uint64_t setpoints_accepted_ = 0;

    std::vector<io::CanFrame> out_;
};

}  // namespace ugv::sim::servo
