#include "pose_node.hpp"

#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>

#include "pose_messages.hpp"
#include "ugv/bus/typed.hpp"
#include "ugv/daemon/input_stamps.hpp"
#include "ugv/estimation/pose_estimator.hpp"
#include "ugv/io/clock.hpp"
#include "ugv/runtime/counters.hpp"
#include "ugv/runtime/rate_limited_log.hpp"

namespace ugv::pose_daemon {
namespace {

const char* degraded_reason(const estimation::PoseEstimate& p)
{
    if (p.status == estimation::PoseStatus::ok) return "";
    if (p.gps_outage) return "GPS outage, prediction only";
    if (!p.heading_observed) return "heading not yet observed (not moving)";
    return "IMU stale";
}

}  // namespace

int run(daemon::Daemon& d, const PoseConfig& cfg)
{
    // Flowing: POSE published (on message time, so it stops when the inputs stop).
    d.declare_output(cfg.channel, 2'000'000);
    estimation::PoseEstimator estimator(cfg.estimator);
    runtime::set_all(d.counters(), estimator.counters());  // listed from the first status message on

    int64_t seq = 0;
    bool first_pose = true;
    estimation::PoseStatus last_status = estimation::PoseStatus::initializing;
    std::string pose_why;  // the pose's own reason for DEGRADED ("" = OK)
    // An input stamped too far from the bus clock never reaches the estimator. While every
    // message of one input is refused the daemon is DEGRADED, saying which; when one is taken
    // again, the pose's own state is back.
    daemon::InputStamps stamps(d, {.max_ahead_us = cfg.max_stamp_ahead_us, .max_age_us = cfg.max_stamp_age_us, .skew = cfg.stamp_skew}, [&] {
        if (first_pose) return;
        d.set_state(pose_why.empty() ? daemon::State::running : daemon::State::degraded, pose_why);
        d.notify_status(pose_why.empty() ? std::string("OK") : "DEGRADED: " + pose_why);
    });
    const int fix_input = stamps.add_input(cfg.gps_fix_channel);
    const int velocity_input = stamps.add_input(cfg.gps_velocity_channel);
    const int imu_input = stamps.add_input(cfg.imu_channel);
    // An input the estimator could not apply at its own time is said once (then every 5 s).
    runtime::RateLimitedLog drop_log;
    estimation::EstimatorCounters seen = estimator.counters();
    const auto log_drops = [&](const std::string& channel, int64_t utime) {
        const estimation::EstimatorCounters& now = estimator.counters();
        if (now.late != seen.late) {
            drop_log.log(spdlog::level::warn, "late",
                         fmt::format("{} stamped {} dropped: older than the history of {} inputs (history_size); "
                                     "late counts them",
                                     channel, utime, cfg.estimator.history_size),
                         io::monotonic_us());
        } else if (now.ahead != seen.ahead) {
            drop_log.log(spdlog::level::warn, "ahead",
                         fmt::format("{} stamped {} dropped: more than max_ahead_of_newest_s ({} s) after the newest "
                                     "input; ahead counts them",
                                     channel, utime, static_cast<double>(cfg.estimator.max_ahead_us) * 1e-6),
                         io::monotonic_us());
        }
        seen = now;
    };
    const auto publish_poses = [&] {
        for (const estimation::PoseEstimate& p : estimator.take_poses()) {
            bus::publish(d.out(), cfg.channel, to_message(p, seq++));
            if (first_pose) {
                d.ready();  // READY=1 and RUNNING; the pose's own status follows
                first_pose = false;
                if (stamps.refusing()) d.set_state(daemon::State::degraded, stamps.reason());
            }
            if (p.status != last_status) {
                // DEGRADED keeps the systemd watchdog fed (the daemon is dead-reckoning, and a
                // restart would lose the filter and a first-fix datum); it is also in
                // pose_t.status, last_error and the STATUS= line.
                last_status = p.status;
                pose_why = degraded_reason(p);
                if (!stamps.refusing()) {  // else refused inputs are the reason shown
                    d.set_state(pose_why.empty() ? daemon::State::running : daemon::State::degraded, pose_why);
                    d.notify_status(pose_why.empty() ? std::string("OK") : "DEGRADED: " + pose_why);
                }
            }
            d.mark_output();
        }
        runtime::set_all(d.counters(), estimator.counters());
    };

    bus::subscribe<gps_fix_t>(d.bus(), cfg.gps_fix_channel, [&](const std::string&, const gps_fix_t& m, int64_t) {
        if (!stamps.accept(fix_input, m.utime)) return;
        estimator.add(to_fix(m));
        log_drops(cfg.gps_fix_channel, m.utime);
        publish_poses();
    });
    bus::subscribe<gps_velocity_t>(d.bus(), cfg.gps_velocity_channel,
                                   [&](const std::string&, const gps_velocity_t& m, int64_t) {
                                       if (!stamps.accept(velocity_input, m.utime)) return;
                                       estimator.add(to_velocity(m));
                                       log_drops(cfg.gps_velocity_channel, m.utime);
                                       publish_poses();
                                   });
    bus::subscribe<imu_t>(d.bus(), cfg.imu_channel, [&](const std::string&, const imu_t& m, int64_t) {
        if (!stamps.accept(imu_input, m.utime)) return;
        estimator.add(to_imu(m));
        log_drops(cfg.imu_channel, m.utime);
        publish_poses();
    });

    spdlog::info("fusing {} + {} + {} -> {} {} {} us, late inputs from a history of {} ({})", cfg.gps_fix_channel,
                 cfg.gps_velocity_channel, cfg.imu_channel, cfg.channel,
                 cfg.estimator.pose_times == estimation::PoseTimes::imu ? "after each IMU sample, at most every"
                                                                          : "every",
                 cfg.estimator.output_period_us, cfg.estimator.history_size,
                 cfg.estimator.datum ? "configured datum" : "datum from the first fix");
    const int rc = d.run();
    if (d.replaying()) {
        estimator.flush();
        publish_poses();
    }
    return rc;
}

}  // namespace ugv::pose_daemon
