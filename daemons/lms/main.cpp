// ugv-lms: one SICK LMS 2xx over RS-422 -> laser_scan_t on LMS_SCAN (and raw_bytes_t on
// RAW_LMS when asked). config -> the sick_lms2xx session on a device thread, which publishes;
// the main thread runs status, systemd and signals. Keys, counters and failure modes: docs/lms.md.
#include <spdlog/spdlog.h>

#include "device_thread.hpp"
#include "lms_config.hpp"
#include "ugv/daemon/daemon.hpp"

int main(int argc, char** argv)
{
    using namespace ugv::lms_daemon;
    ugv::daemon::Daemon d({.name = "ugv-lms", .status_channel = "STATUS_LMS", .default_config = "/etc/ugv/lms.toml"},
                          argc, argv);
    const LmsConfig config = read_config(d.config());
    d.start();

    // Every counter exists from the first status message on.
    for (const char* name : {"scans", "crc_errors", "resyncs", "naks", "timeouts", "reconnects", "bytes_in",
                             "bad_scans", "clock_restarts", "published", "publish_failures"})
        d.counters()[name];
    DeviceThread device(d, config);
    int ticks = 0;
    d.add_timer(200'000, [&] {
        device.publish_counters();
        if (device.streaming()) d.ready();
        if (++ticks % 5 != 0) return;  // the systemd status line once a second
        d.notify_status(device.streaming() ? "streaming, " + std::to_string(d.counters().get("scans")) + " scans"
                                           : "looking for the LMS on " + config.device);
    });
    spdlog::info("{} at {} baud, {} deg / {} deg, {} -> {}", config.device, config.session.baud,
                 config.session.angle_deg, config.session.resolution_cdeg / 100.0,
                 config.session.units == ugv::sick_lms2xx::Units::mm ? "mm" : "cm", config.channel);
    device.start();
    const int rc = d.run();
    d.request_stop();
    device.join();
    return rc;
}
