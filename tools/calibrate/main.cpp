// ugv-calibrate: mounts estimated from a log (docs/calibration.md).
//   ugv-calibrate laser LOG [--mount-config nodscan.toml] [--json]
//       the nodding laser's tilt axis roll, pitch (= the servo's tilt zero), yaw and height
//       from a recording of flat ground (laser_command.hpp).
//   ugv-calibrate imu LOG [--mount-config imu.toml] [--json]
//       the IMU's mounting from standing still and straight acceleration (imu_command.hpp).
//   ugv-calibrate antenna LOG [--pose-config pose.toml] [--json]
//       the GPS antenna's lever arm from a drive with turns (antenna_command.hpp).
// Exit status: 0 with an estimate, 2 when the log cannot give one (the reason in one line).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>

#include "antenna_command.hpp"
#include "imu_command.hpp"
#include "laser_command.hpp"

int main(int argc, char** argv)
{
    CLI::App app{"mounts estimated from a log instead of a tape measure"};
    app.set_version_flag("--version", std::string("ugv-calibrate ") + UGV_VERSION);
    app.require_subcommand(1);
    ugv::calibrate_tool::LaserCommand laser(app);
    ugv::calibrate_tool::ImuCommand imu(app);
    ugv::calibrate_tool::AntennaCommand antenna(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : 2;
    }
    if (laser.chosen()) return laser.run();
    if (imu.chosen()) return imu.run();
    if (antenna.chosen()) return antenna.run();
    return 2;
}
