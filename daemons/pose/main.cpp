// ugv-pose: GPS_FIX + GPS_VEL + IMU -> POSE, a 6-DOF pose with covariance in local ENU at a
// fixed rate of data time (docs/pose.md). Driven by message utime only, so --replay LOG
// --out LOG is deterministic.
#include <spdlog/spdlog.h>

#include "pose_config.hpp"
#include "pose_messages.hpp"
#include "ugv/bus/typed.hpp"
#include "ugv/daemon/daemon.hpp"

using namespace ugv;

int main(int argc, char** argv)
{
    daemon::Daemon d({.name = "ugv-pose", .status_channel = "STATUS_POSE", .processing = true, .bus_batch_ms = 50}, argc, argv);
    const pose_daemon::PoseConfig cfg = pose_daemon::read_config(d.config());
    d.start();

    estimation::PoseEstimator estimator(cfg.estimator);
    auto& c = d.counters();
    const char* names[] = {"poses",        "gps_used",      "gps_rejected",      "gps_low_quality", "gps_resets",
                           "velocity_used", "velocity_rejected", "course_used", "course_rejected", "imu_used",
                           "imu_rejected", "late",          "reordered",         "outages",         "non_finite",
                           "filter_resets", "duplicates"};
    for (const char* n : names) c[n] = 0;
    const auto sync_counters = [&] {
        const estimation::EstimatorCounters& n = estimator.counters();
        c["poses"] = n.poses;
        c["gps_used"] = n.gps_used;
        c["gps_rejected"] = n.gps_rejected;
        c["gps_low_quality"] = n.gps_low_quality;
        c["gps_resets"] = n.gps_resets;
        c["velocity_used"] = n.velocity_used;
        c["velocity_rejected"] = n.velocity_rejected;
        c["course_used"] = n.course_used;
        c["course_rejected"] = n.course_rejected;
        c["imu_used"] = n.imu_used;
        c["imu_rejected"] = n.imu_rejected;
        c["late"] = n.late;
        c["reordered"] = n.reordered;
        c["duplicates"] = n.duplicates;
        c["outages"] = n.outages;
        c["non_finite"] = n.non_finite;
        c["filter_resets"] = n.filter_resets;
    };

    int64_t seq = 0;
    bool first_pose = true;
    estimation::PoseStatus last_status = estimation::PoseStatus::initializing;
    const auto publish_poses = [&] {
        for (const estimation::PoseEstimate& p : estimator.take_poses()) {
            bus::publish(d.out(), cfg.channel, pose_daemon::to_message(p, seq++));
            if (first_pose) {
                d.ready();  // READY=1 and RUNNING; the pose's own status follows
                first_pose = false;
            }
            if (p.status != last_status) {
                // DEGRADED keeps the systemd watchdog fed (the daemon is dead-reckoning, and a
                // restart would lose the filter and a first-fix datum); it is also in
                // pose_t.status, last_error and the STATUS= line.
                last_status = p.status;
                const char* why = p.status == estimation::PoseStatus::ok ? ""
                                  : p.gps_outage                        ? "GPS outage, prediction only"
                                  : !p.heading_observed ? "heading not yet observed (not moving)"
                                                        : "IMU stale";
                d.set_state(*why ? daemon::State::degraded : daemon::State::running, why);
                d.notify_status(*why ? std::string("DEGRADED: ") + why : std::string("OK"));
            }
            d.mark_alive();
        }
        sync_counters();
    };

    bus::subscribe<gps_fix_t>(d.bus(), cfg.gps_fix_channel, [&](const std::string&, const gps_fix_t& m, int64_t) {
        estimator.add(pose_daemon::to_fix(m));
        publish_poses();
    });
    bus::subscribe<gps_velocity_t>(d.bus(), cfg.gps_velocity_channel,
                                   [&](const std::string&, const gps_velocity_t& m, int64_t) {
                                       estimator.add(pose_daemon::to_velocity(m));
                                       publish_poses();
                                   });
    bus::subscribe<imu_t>(d.bus(), cfg.imu_channel, [&](const std::string&, const imu_t& m, int64_t) {
        estimator.add(pose_daemon::to_imu(m));
        publish_poses();
    });

    spdlog::info("fusing {} + {} + {} -> {} every {} us ({})", cfg.gps_fix_channel, cfg.gps_velocity_channel,
                 cfg.imu_channel, cfg.channel, cfg.estimator.output_period_us,
                 cfg.estimator.datum ? "configured datum" : "datum from the first fix");
    const int rc = d.run();
    if (d.replaying()) {
        // The end of the log: what is still in the reorder buffer becomes poses too.
        estimator.flush();
        publish_poses();
    }
    return rc;
}
