// ugv-calibrate: mounts estimated from a log (docs/calibration.md).
//   ugv-calibrate laser LOG [--mount-config nodscan.toml] [--json]
//       the nodding laser's tilt axis roll, pitch (= the servo's tilt zero), yaw and height
//       from a recording of flat ground (laser_command.hpp).
// Exit status: 0 with an estimate, 2 when the log cannot give one (the reason in one line).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>

#include "laser_command.hpp"

int main(int argc, char** argv)
{
    CLI::App app{"mounts estimated from a log instead of a tape measure"};
    app.set_version_flag("--version", std::string("ugv-calibrate ") + UGV_VERSION);
    app.require_subcommand(1);
    ugv::calibrate_tool::LaserCommand laser(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e) == 0 ? 0 : 2;
    }
    if (laser.chosen()) return laser.run();
    return 2;
}
