#include "pose_node.hpp"

#include <spdlog/spdlog.h>

#include "pose_messages.hpp"
#include "ugv/bus/typed.hpp"
#include "ugv/estimation/pose_estimator.hpp"
#include "ugv/runtime/counters.hpp"

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
    const auto publish_poses = [&] {
        for (const estimation::PoseEstimate& p : estimator.take_poses()) {
            bus::publish(d.out(), cfg.channel, to_message(p, seq++));
            if (first_pose) {
                d.ready();  // READY=1 and RUNNING; the pose's own status follows
                first_pose = false;
            }
            if (p.status != last_status) {
                // DEGRADED keeps the systemd watchdog fed (the daemon is dead-reckoning, and a
                // restart would lose the filter and a first-fix datum); it is also in
                // pose_t.status, last_error and the STATUS= line.
                last_status = p.status;
                const char* why = degraded_reason(p);
                d.set_state(*why ? daemon::State::degraded : daemon::State::running, why);
                d.notify_status(*why ? std::string("DEGRADED: ") + why : std::string("OK"));
            }
            d.mark_output();
        }
        runtime::set_all(d.counters(), estimator.counters());
    };

    bus::subscribe<gps_fix_t>(d.bus(), cfg.gps_fix_channel, [&](const std::string&, const gps_fix_t& m, int64_t) {
        estimator.add(to_fix(m));
        publish_poses();
    });
    bus::subscribe<gps_velocity_t>(d.bus(), cfg.gps_velocity_channel,
                                   [&](const std::string&, const gps_velocity_t& m, int64_t) {
                                       estimator.add(to_velocity(m));
                                       publish_poses();
                                   });
    bus::subscribe<imu_t>(d.bus(), cfg.imu_channel, [&](const std::string&, const imu_t& m, int64_t) {
        estimator.add(to_imu(m));
        publish_poses();
    });

    spdlog::info("fusing {} + {} + {} -> {} every {} us ({})", cfg.gps_fix_channel, cfg.gps_velocity_channel,
                 cfg.imu_channel, cfg.channel, cfg.estimator.output_period_us,
                 cfg.estimator.datum ? "configured datum" : "datum from the first fix");
    const int rc = d.run();
    if (d.replaying()) {
        estimator.flush();
        publish_poses();
    }
    return rc;
}

}  // namespace ugv::pose_daemon
