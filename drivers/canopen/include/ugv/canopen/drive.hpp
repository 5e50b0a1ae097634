// One CiA 402 servo drive in profile position mode, as a session without I/O: feed it the
// frames the bus delivered and the time, call tick() often (every few ms), and send what
// take_outgoing() returns. The daemon owns the transport and the retry back-off.
//
// Start-up: NMT pre-operational; the probe (SDO reads of identity, objects, PDO resources
// and mapping rights: plan.hpp), the plan; SDO: heartbeat producer time (0x1017), the
// planned PDOs (TPDO statusword + position actual, velocity actual; RPDO target position +
// controlword, profile velocity), mode 1 (0x6060), acceleration/deceleration (0x6083/0x6084);
// a mapping write the drive refuses is learnt and the plan made again; NMT start; on the
// first position TPDO the target is set to the actual position (so no stale 0x607A moves the
// axis) and the state machine is walked to Operation Enabled. A fault is reset and the drive enabled again; a lost heartbeat,
// a failed SDO or an enable that does not succeed puts the session in Phase::failed.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "ugv/canopen/cia402.hpp"
#include "ugv/canopen/nmt.hpp"
#include "ugv/canopen/pdo.hpp"
#include "ugv/canopen/plan.hpp"
#include "ugv/canopen/plausibility.hpp"
#include "ugv/canopen/sdo.hpp"
#include "ugv/canopen/setpoint.hpp"
#include "ugv/canopen/units.hpp"
#include "ugv/io/can_frame.hpp"
#include "ugv/io/periodic_clock.hpp"

namespace ugv::canopen {

struct DriveConfig
{
    uint8_t node_id = 1;
    UnitConversion units;
    double min_angle_rad = -0.5;  // set-points are clamped into [min, max] (the last guard)
    double max_angle_rad = 0.5;
    int heartbeat_period_ms = 100;   // written to 0x1017; lost after 3 missed beats
    int64_t sdo_timeout_us = 200'000;
    int sdo_retries = 1;
    int tpdo_period_ms = 10;         // TPDO event timer when there is no SYNC (100 Hz)
    int64_t sync_period_us = 0;      // > 0: produce SYNC and send TPDOs on every SYNC
    double acceleration_rad_s2 = 20.0;  // 0x6083 / 0x6084
    double max_velocity_rad_s = 3.0;    // profile velocity cap
    int64_t start_timeout_us = 1'000'000;  // NMT start -> first TPDO1
    cia402::Enabler::Options enabler;
    int64_t setpoint_timeout_us = 200'000;
    int64_t halt_timeout_us = 500'000;
    // Set when the link to the drive has no checksum (slcan's ASCII lines; CAN itself has a
    // CRC): a bit error there can turn a TPDO into another well-formed one. Then a TPDO1 whose
    // position TPDO is taken at once only next to a taken one within one drive period's
    // travel with the same state (TpdoPlausibility); others wait for the next to confirm
    // them; one never confirmed is dropped and counted (tpdo_implausible). A velocity TPDO
    // beyond twice the cap is dropped and counted too. Costs one TPDO period of delay on a
    // real state change and after a lost frame.
    bool check_tpdo_plausibility = false;
};

struct DriveSample
{
    int64_t utime = 0;          // receive time of the TPDO1 that carried the position
    int32_t counts = 0;
    double angle_rad = 0.0;
    double velocity_rad_s = 0.0;  // from the latest TPDO2
    double target_rad = 0.0;
    uint16_t statusword = 0;
    cia402::State state = cia402::State::unknown;
};

struct DriveEvent
{
    enum class Level { info, warning, error };
    Level level = Level::info;
    std::string text;
};

struct DriveCounters
{
    uint64_t sdo_timeouts = 0;
    uint64_t sdo_aborts = 0;
    uint64_t emcy = 0;
    uint64_t heartbeat_losses = 0;
    uint64_t faults = 0;           // entries into Fault (or fault reaction)
    uint64_t fault_resets = 0;
    uint64_t enable_failures = 0;
    uint64_t setpoints_acknowledged = 0;
    uint64_t setpoint_timeouts = 0;
    uint64_t tpdo_received = 0;
    uint64_t tpdo_implausible = 0;  // TPDOs dropped by check_tpdo_plausibility
    uint64_t clock_restarts = 0;    // TPDO1 stamp clock restarts (ugv/io/periodic_clock.hpp)
    uint64_t replans = 0;           // mapping writes refused during configuration: plan made again
    uint64_t mandatory_missing = 0; // 1 while the drive lacks a mandatory object
    // The plan's degradations (plan.hpp PlanFlags), 0/1.
    PlanFlags plan;

    template <class F>
    void visit(F&& f) const
    {
        f("sdo_timeouts", sdo_timeouts);
        f("sdo_aborts", sdo_aborts);
        f("emcy", emcy);
        f("heartbeat_losses", heartbeat_losses);
        f("faults", faults);
        f("fault_resets", fault_resets);
        f("enable_failures", enable_failures);
        f("setpoints_acknowledged", setpoints_acknowledged);
        f("setpoint_timeouts", setpoint_timeouts);
        f("tpdo_received", tpdo_received);
        f("tpdo_implausible", tpdo_implausible);
        f("clock_restarts", clock_restarts);
        f("replans", replans);
        f("mandatory_missing", mandatory_missing);
        f("degraded_fixed_mapping", uint64_t{plan.fixed_mapping});
        f("degraded_split_status", uint64_t{plan.split_status});
        f("degraded_velocity_derived", uint64_t{plan.velocity_derived});
        f("degraded_profile_velocity_sdo", uint64_t{plan.profile_velocity_sdo});
        f("degraded_setpoint_sdo", uint64_t{plan.setpoint_sdo});
        f("degraded_supervised_by_tpdo", uint64_t{plan.supervised_by_tpdo});
        f("degraded_sync_only", uint64_t{plan.sync_only});
        f("degraded_no_acceleration", uint64_t{plan.no_acceleration});
    }
};

class Drive
{
public:
    enum class Phase { idle, configuring, starting, enabling, operational, halting, disabling, stopped, failed, probed };

    explicit Drive(DriveConfig config);

    // (Re-)initialises from scratch: drops queued transfers, probes the drive, plans and
    // configures. probe_only: stop after the plan (Phase::probed), writing nothing but the
    // mapping-rights probes (which restore what they change); the axis never moves.
    void start(int64_t now_us, bool probe_only = false);
    // Halt, then disable (switch the power stage off). Ends in Phase::stopped.
    void stop(int64_t now_us);

    // utime: the frame's receive time. Without SYNC a TPDO1's sample is stamped on the
    // drive's own event-timer cadence (io::PeriodicClock), so TPDOs read together after a
    // host stall keep their own times. read_late: utime is only when a batched read found
    // the frame (io::PeriodicClock::update_read_late), not when it arrived; the caller still
    // reads some TPDO1s promptly (see ugv-servo's wake windows). Ignored with SYNC, whose
    // callers must read promptly.
    void on_frame(const io::CanFrame& frame, int64_t now_us, int64_t utime, bool read_late = false);
    // A frame was lost on the way (a malformed slcan line): it may have been a TPDO1.
    void note_lost_frame()
    {
        ++lost_frames_;
        plausibility_.note_lost();
    }
    void tick(int64_t now_us);

    // The next set-point (rad, clamped into the configured limits) and the speed to move
    // there (rad/s, capped). Sent through the handshake when operational.
    void command(double angle_rad, double velocity_rad_s);

    std::vector<io::CanFrame> take_outgoing();
    std::vector<DriveSample> take_samples();
    std::vector<DriveEvent> take_events();

    Phase phase() const { return phase_; }
    bool operational() const { return phase_ == Phase::operational; }
    const std::string& failure() const { return failure_; }
    // The failure is a missing mandatory object (retrying cannot help until the drive changes).
    bool mandatory_missing() const { return mandatory_missing_; }
    const DriveCapabilities& capabilities() const { return caps_; }
    const Plan& plan() const { return plan_; }
    // Whether any frame at all arrived since start(): a session that failed without one
    // points at power, wiring or the bitrate rather than at the drive's answers.
    bool heard_since_start() const { return frames_since_start_ > 0; }
    DriveCounters counters() const;
    std::optional<DriveSample> last_sample() const { return last_; }
    uint16_t last_emcy_code() const { return last_emcy_code_; }
    const DriveConfig& config() const { return config_; }

    static const char* to_string(Phase phase);

private:
    void fail(const std::string& why);
    void event(DriveEvent::Level level, std::string text);
    void queue_probe();
    void probe_pdo(PdoResource& r);
    // True (and the session failed, once) when a probe transfer timed out.
    bool probe_timed_out(const char* what, SdoAddress at, const SdoResult& r);
    void probe_mapping_entry(PdoResource* r, uint16_t map, uint32_t count, uint8_t sub);
    void make_plan();
    void queue_configuration();
    // A configuration write the drive refused: learnt into the capabilities when it is a
    // refusal of a mapping or transmission type (then planned again), else a failure.
    void on_config_refused(const SdoWrite& w, const SdoResult& r);
    PdoResource* resource_of(uint16_t index);
    void on_tpdo1(uint16_t statusword, int32_t counts, int64_t now_us, int64_t utime);
    int64_t drive_period_us() const;
    void send_rpdos(bool force);
    uint32_t rpdo_value(uint16_t index, uint16_t cw) const;
    void sdo_write_runtime(uint16_t index, uint32_t value, int size);

    DriveConfig config_;
    uint8_t node_;
    Phase phase_ = Phase::idle;
    std::string failure_;
    SdoClient sdo_;
    HeartbeatConsumer heartbeat_;
    cia402::Enabler enabler_;
    cia402::SetpointHandshake setpoint_;
    DriveCapabilities caps_;
    Plan plan_;
    bool probe_only_ = false;
    bool probing_ = false;
    std::string probe_error_;
    bool mandatory_missing_ = false;
    int replans_in_session_ = 0;
    int64_t last_tpdo_us_ = 0;
    uint16_t latest_statusword_ = 0;

    int64_t phase_us_ = 0;
    uint64_t frames_since_start_ = 0;
    int64_t next_sync_us_ = 0;
    bool config_done_ = false;
    bool halt_ = false;
    cia402::State last_state_ = cia402::State::unknown;
    double velocity_rad_s_ = 0.0;
    std::optional<DriveSample> last_;
    TpdoPlausibility plausibility_;
    uint64_t plausibility_dropped_ = 0;  // by the checkers of earlier sessions
    io::PeriodicClock tpdo1_clock_{0.01};
    int lost_frames_ = 0;
    uint16_t last_emcy_code_ = 0;

    // What the drive was last sent through the RPDOs (send only changes, and on retries).
    std::optional<std::pair<int32_t, uint16_t>> sent_rpdo1_;
    std::optional<uint32_t> sent_velocity_;
    std::optional<int32_t> sent_target_sdo_;
    std::optional<uint16_t> sent_cw_sdo_;

    DriveCounters counters_;
    std::vector<io::CanFrame> out_;
    std::vector<DriveSample> samples_;
    std::vector<DriveEvent> events_;
};

}  // namespace ugv::canopen
