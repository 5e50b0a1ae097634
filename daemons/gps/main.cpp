// ugv-gps: NovAtel OEM4-family / Sokkia GSR2600 receiver -> GPS_FIX, GPS_VEL (and RAW_GPS).
// config -> ugv_novatel (decode, interpret, session) -> bus. docs/gps.md has the keys.
#include "gps_config.hpp"
#include "gps_node.hpp"

int main(int argc, char** argv)
{
    ugv::daemon::Daemon d({.name = "ugv-gps", .status_channel = "STATUS_GPS"}, argc, argv);
    // A bad key throws ConfigError: the Daemon prints `FILE: KEY: why` and exits 2.
    const ugv::gps_daemon::GpsConfig config = ugv::gps_daemon::read_config(d.config());
    d.start();
    return ugv::gps_daemon::run(d, config);
}
