// ugv-nodscan: LMS_SCAN + SERVO_STATE -> POINTS (3-D points in the body frame with variance).
#include <spdlog/spdlog.h>

#include "nodscan_config.hpp"
#include "nodscan_node.hpp"
#include "ugv/bus/typed.hpp"
#include "ugv/daemon/daemon.hpp"
#include "ugv/io/clock.hpp"

using namespace ugv;

int main(int argc, char** argv)
{
    daemon::Daemon d({.name = "ugv-nodscan", .status_channel = "STATUS_NODSCAN", .processing = true, .bus_batch_ms = 50}, argc, argv);
    const nodscan_daemon::NodscanConfig cfg = nodscan_daemon::read_config(d.config());
    d.start();

    auto& c = d.counters();
    const char* names[] = {"scans_in", "scans_out", "points_out", "dropped_invalid", "dropped_no_angle",
                           "scans_without_servo", "scans_overflow", "servo_rejected", "scans_other_sensor"};
    for (const char* n : names) c[n] = 0;

    nodscan_daemon::NodscanNode node(cfg, [&d, &cfg](const point_cloud_t& msg) {
        bus::publish(d.out(), cfg.channel, msg);
        d.mark_alive();
        d.ready();
    });
    const auto sync_counters = [&] {
        const auto& n = node.counters();
        c["scans_in"] = static_cast<int64_t>(n.scans_in);
        c["scans_out"] = static_cast<int64_t>(n.scans_out);
        c["points_out"] = static_cast<int64_t>(n.points_out);
        c["dropped_invalid"] = static_cast<int64_t>(n.dropped_invalid);
        c["dropped_no_angle"] = static_cast<int64_t>(n.dropped_no_angle);
        c["scans_without_servo"] = static_cast<int64_t>(n.scans_without_servo);
        c["scans_overflow"] = static_cast<int64_t>(n.scans_overflow);
        c["servo_rejected"] = static_cast<int64_t>(n.servo_rejected);
        c["scans_other_sensor"] = static_cast<int64_t>(n.scans_other_sensor);
    };
    bus::subscribe<servo_state_t>(d.bus(), cfg.servo_channel,
                                  [&](const std::string&, const servo_state_t& m, int64_t) {
                                      node.on_servo(m);
                                      sync_counters();
                                  });
    bus::subscribe<laser_scan_t>(d.bus(), cfg.scan_channel, [&](const std::string&, const laser_scan_t& m, int64_t) {
        node.on_scan(m);
        sync_counters();
    });
    if (!d.replaying()) {
        // Live: a scan whose servo stream stalled is not held longer than max_wait of wall time.
        d.add_timer(cfg.max_wait_us > 0 ? cfg.max_wait_us : 10'000, [&] {
            node.flush_older_than(io::now_utime() - cfg.max_wait_us);
            sync_counters();
        });
    }
    spdlog::info("assembling {} + {} -> {}", cfg.scan_channel, cfg.servo_channel, cfg.channel);
    const int rc = d.run();
    return rc;
}
