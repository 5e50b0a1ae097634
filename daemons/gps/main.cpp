// ugv-gps: NovAtel OEM4-family / Sokkia GSR2600 receiver -> GPS_FIX, GPS_VEL (and RAW_GPS).
// config -> ugv_novatel (decode, interpret, session) -> bus. docs/gps.md has the keys.
#include <thread>

#include "gps_config.hpp"
#include "receiver_loop.hpp"
#include "ugv/daemon/daemon.hpp"

int main(int argc, char** argv)
{
    ugv::daemon::Daemon d({.name = "ugv-gps", .status_channel = "STATUS_GPS", .processing = false,
                           .default_config = ""},
                          argc, argv);
    // A bad key throws ConfigError: the Daemon prints `FILE: KEY: why` and exits 2.
    const ugv::gps::GpsConfig config = ugv::gps::read_gps_config(d.config());
    d.start();
    ugv::gps::ReceiverLoop loop(d, config);
    std::thread device;
    // The bus's publishing side exists once run() has started: start the device thread from
    // the main loop, which also sends READY=1 once fixes flow.
    d.add_timer(100'000, [&] {
        if (!device.joinable()) {
            device = std::thread([&] { loop.run(); });
        }
        if (loop.data_flowing() && d.state() != ugv::daemon::State::degraded) {
            d.ready();
        }
    });
    const int rc = d.run();
    if (device.joinable()) {
        device.join();
    }
    return rc;
}
