// ugv-imu: MicroStrain 3DM-GX1 -> imu_t on IMU (body FLU -> world ENU). config -> the
// microstrain_gx1 session on a device thread -> outbox -> bus (main thread). Keys and
// behaviour: docs/imu.md.
#include <thread>
#include <vector>

#include "device_loop.hpp"
#include "imu_config.hpp"
#include "outbox.hpp"
#include "ugv/bus/typed.hpp"
#include "ugv/daemon/daemon.hpp"

int main(int argc, char** argv)
{
    ugv::daemon::Daemon d({.name = "ugv-imu", .status_channel = "STATUS_IMU", .default_config = "/etc/ugv/imu.toml"},
                          argc, argv);
    const ugv::imu_daemon::ImuConfig config = ugv::imu_daemon::read_config(d.config());
    d.start();

    ugv::imu_daemon::Outbox outbox;
    ugv::imu_daemon::DeviceLoop loop(d, config, outbox);  // registers the device counters first
    auto& published = d.counters()["published"];
    auto& publish_failures = d.counters()["publish_failures"];
    d.add_fd(outbox.fd(), [&] {
        std::vector<ugv::imu_t> imu;
        std::vector<ugv::raw_bytes_t> raw;
        outbox.take(imu, raw);
        for (const auto& m : raw)
            if (!ugv::bus::publish(d.out(), config.raw_channel, m)) ++publish_failures;
        for (const auto& m : imu) {
            if (ugv::bus::publish(d.out(), config.channel, m))
                ++published;
            else
                ++publish_failures;
        }
    });

    std::thread device([&loop] { loop.run(); });
    const int rc = d.run();
    d.request_stop();
    device.join();
    return rc;
}
