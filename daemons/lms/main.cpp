// ugv-lms: one SICK LMS 2xx over RS-422 -> laser_scan_t on LMS_SCAN (and raw_bytes_t on
// RAW_LMS when asked). config -> the sick_lms2xx session on a device thread, which publishes;
// the main thread runs status, systemd and signals. Keys, counters and failure modes: docs/lms.md.
#include "lms_config.hpp"
#include "lms_node.hpp"

int main(int argc, char** argv)
{
    ugv::daemon::Daemon d({.name = "ugv-lms", .status_channel = "STATUS_LMS", .default_config = "/etc/ugv/lms.toml"},
                          argc, argv);
    const ugv::lms_daemon::LmsConfig config = ugv::lms_daemon::read_config(d.config());
    d.start();
    return ugv::lms_daemon::run(d, config);
}
