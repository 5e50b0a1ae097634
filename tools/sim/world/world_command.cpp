// ugv-sim world: one simulated vehicle driving all four device emulators from one clock.
//
//   ugv-sim world --run-dir DIR [--scenario FILE] [--lcm-url URL] [--duration S]
//   ugv-sim world --print-scenario        (the default scenario, a starting point for others)
//
// The run folder gets the device links (lms, servo, gps, imu; with [[laser]] tables
// lms-NAME and servo-NAME per laser), truth.hf, scenario.toml, calibration/{nodscan,pose,imu}.toml
// (nodscan-NAME.toml and servo-NAME.toml per named laser; the mounts the daemons are told),
// true-calibration/ (the same files with the true mounts), and `ready` once every device is
// up. SIM_TRUTH (sim_truth_t, servo_angle of the first laser) goes out at 100 Hz. It ends after the scenario's path and hold time, after
// --duration, or on SIGINT/SIGTERM.
//
// One thread: poll() on the pty masters with a 1 ms timeout, then every device is
// serviced with the same clock reading, so the servo's encoder, the laser's beams, the GPS
// fixes and the IMU samples all come from one truth.
#include <poll.h>
#include <sys/stat.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "device_ports.hpp"
#include "loop_lateness.hpp"
#include "run_folder.hpp"
#include "ugv/bus/bus.hpp"
#include "ugv/bus/typed.hpp"
#include "ugv/io/clock.hpp"
#include "ugv/runtime/config.hpp"
#include "ugv/runtime/stop_signals.hpp"
#include "ugv/sim/command.hpp"
#include "ugv/sim/parse_command_line.hpp"
#include "ugv/sim_truth_t.hpp"

namespace {

using namespace ugv::sim::world;
namespace sw = ugv::simworld;

ugv::sim_truth_t truth_message(const sw::World& world, const sw::TruthState& s, double tilt_rad, int64_t seq,
                               const std::string& scenario_name)
{
    ugv::sim_truth_t m{};
    m.utime = s.utime;
    m.seq = seq;
    for (int i = 0; i < 3; ++i) {
        m.position[i] = s.position_m[i];
        m.velocity[i] = s.velocity_mps[i];
    }
    m.orientation[0] = s.orientation.w();
    m.orientation[1] = s.orientation.x();
    m.orientation[2] = s.orientation.y();
    m.orientation[3] = s.orientation.z();
    m.roll = s.roll_rad;
    m.pitch = s.pitch_rad;
    m.yaw = s.yaw_rad;
    m.servo_angle = tilt_rad;
    m.datum_latitude = world.scenario().datum_latitude_deg;
    m.datum_longitude = world.scenario().datum_longitude_deg;
    m.datum_height = world.scenario().datum_height_m;
    m.scenario = scenario_name;
    return m;
}

int run(const std::string& dir, const std::string& scenario_toml, const std::string& scenario_file,
        const std::string& url, double duration_s, uint32_t seed, const ugv::sim::lms::DeviceOptions& lms_timing)
{
    ugv::runtime::Config cfg = ugv::runtime::Config::parse(scenario_toml, scenario_file);
    const sw::Scenario scenario = sw::parse_scenario(cfg);
    if (::mkdir(dir.c_str(), 0755) != 0 && errno != EEXIST) {
        std::fprintf(stderr, "ugv-sim world: %s: %s\n", dir.c_str(), std::strerror(errno));
        return 1;
    }
    auto bus = ugv::bus::open_live(url);
    // The path starts a little after the devices appear, so the first truth is not in the past.
    const int64_t start = ugv::io::now_utime() + 200'000;
    const sw::World world(scenario, start);
    write_run_folder(dir, world, scenario_toml);

    // Per laser: its servo's tilt history, its servo, its LMS. Servos come first in `all`, so
    // the laser's beams read the tilt their servo just recorded.
    const std::size_t n_lasers = scenario.lasers.size();
    std::vector<std::unique_ptr<TiltHistory>> tilts;
    std::vector<std::unique_ptr<DevicePort>> servos, ports;
    const int64_t now0 = ugv::io::now_utime();
    for (std::size_t k = 0; k < n_lasers; ++k) {
        const sw::LaserSpec& laser = scenario.lasers[k];
        tilts.push_back(std::make_unique<TiltHistory>());
        if (scenario.devices.servo)
            servos.push_back(std::make_unique<ServoPort>(dir + "/servo" + laser.suffix(), laser.servo, now0, *tilts[k]));
        // The first laser keeps the seed a one-laser world always had.
        if (scenario.devices.lms)
            ports.push_back(std::make_unique<LmsPort>(dir + "/lms" + laser.suffix(), world, k, *tilts[k],
                                                      seed + (k == 0 ? 0U : 2U + static_cast<uint32_t>(k)), lms_timing));
    }
    if (scenario.devices.gps) ports.push_back(std::make_unique<GpsPort>(dir + "/gps", world, now0, seed + 1));
    if (scenario.devices.imu) ports.push_back(std::make_unique<ImuPort>(dir + "/imu", world, now0, seed + 2));
    write_file(dir + "/ready", "");
    const int64_t end = duration_s > 0 ? start + static_cast<int64_t>(duration_s * 1e6) : world.end_utime();
    std::fprintf(stderr, "ugv-sim world: scenario %s, %.1f s, devices in %s; truth on SIM_TRUTH\n",
                 scenario.name.c_str(), static_cast<double>(end - start) * 1e-6, dir.c_str());

    std::vector<DevicePort*> all;
    for (auto& p : servos) all.push_back(p.get());
    for (auto& p : ports) all.push_back(p.get());
    std::vector<pollfd> fds(all.size());
    int64_t next_truth = start, seq = 0;
    std::size_t dropped = 0;
    LoopLateness lateness;
    while (!ugv::runtime::stop_requested()) {
        for (std::size_t i = 0; i < all.size(); ++i) fds[i] = {all[i]->fd(), POLLIN, 0};
        ::poll(fds.data(), fds.size(), 1);
        const int64_t now = ugv::io::now_utime();
        if (now >= end) break;
        lateness.add(now);
        for (std::size_t i = 0; i < all.size(); ++i) dropped += all[i]->service((fds[i].revents & POLLIN) != 0, now);
        // Truth on a fixed 10 ms grid: after a stall of the simulator the instants it missed
        // are sent late but with their own time (up to one second of them).
        if (now - next_truth > 1'000'000) next_truth = now;
        while (now >= next_truth) {
            const sw::TruthState s = world.truth(next_truth);
            ugv::bus::publish(*bus, "SIM_TRUTH", truth_message(world, s, tilts[0]->at(next_truth), seq++, scenario.name));
            next_truth += 10'000;
        }
    }
    std::fprintf(stderr, "ugv-sim world: %s; %lld truth messages, %zu device bytes not taken by the host\n",
                 ugv::runtime::stop_requested() ? "stopped" : "scenario done", static_cast<long long>(seq), dropped);
    for (const DevicePort* p : all) std::fprintf(stderr, "ugv-sim world: %s\n", p->summary().c_str());
    std::fprintf(stderr, "ugv-sim world: %s\n", lateness.summary().c_str());
    return 0;
}

int world_main(int argc, char** argv)
{
    CLI::App app{"one simulated vehicle driving all four device emulators (SICK LMS, CAN servo, GPS, IMU)", argv[0]};
    std::string dir, scenario_path, url;
    double duration_s = 0;
    unsigned seed = 1;
    bool print = false;
    app.add_option("--run-dir", dir, "folder for the device links, truth.hf, calibration/ and the ready marker");
    app.add_option("--scenario", scenario_path, "scenario TOML (default: the report's demonstration)");
    app.add_option("--lcm-url", url, "LCM URL for SIM_TRUTH (default: LCM_DEFAULT_URL)");
    app.add_option("--duration", duration_s, "end after S seconds instead of at the end of the path")
        ->check(CLI::Range(0.0, 1e6));
    app.add_option("--seed", seed, "noise seed");
    app.add_flag("--print-scenario", print, "print the default scenario and exit");
    std::string lms_timing = "interlaced";
    std::vector<std::string> lms_orders;
    app.add_option("--lms-timing", lms_timing, "the LMS's beam times: interlaced sweeps as the device does, or linear")
        ->check(CLI::IsMember({"interlaced", "linear"}));
    app.add_option("--lms-sweep-order", lms_orders,
                   "beam phase measured by each LMS sweep: 2 digits for 0.5 deg (01, 10), 4 for 0.25 deg "
                   "(e.g. 0123); repeatable");
    if (const auto status = ugv::sim::parse_command_line(app, argc, argv)) return *status;
    if (print) {
        std::fputs(ugv::simworld::default_scenario_toml(), stdout);
        return 0;
    }
    if (dir.empty()) {
        std::fprintf(stderr, "%s: --run-dir is required\n", argv[0]);
        return 2;
    }
    std::string text = ugv::simworld::default_scenario_toml(), name = "<default scenario>";
    if (!scenario_path.empty()) {
        std::ifstream in(scenario_path);
        if (!in) {
            std::fprintf(stderr, "%s: %s: cannot read the scenario\n", argv[0], scenario_path.c_str());
            return 2;
        }
        std::stringstream ss;
        ss << in.rdbuf();
        text = ss.str();
        name = scenario_path;
    }
    ugv::sim::lms::DeviceOptions timing;
    timing.linear_timing = lms_timing == "linear";
    for (const std::string& o : lms_orders)
        if (!ugv::sim::lms::set_sweep_order(timing, o)) {
            std::fprintf(stderr, "%s: --lms-sweep-order: '%s' is not an order of 2 or 4 beam phases (e.g. 10, 0213)\n",
                         argv[0], o.c_str());
            return 2;
        }
    ugv::runtime::install_stop_signals();
    try {
        return run(dir, text, name, url, duration_s, seed, timing);
    } catch (const ugv::runtime::ConfigError& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 2;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", argv[0], e.what());
        return 1;
    }
}

}  // namespace

UGV_SIM_COMMAND("world", "one simulated vehicle (scenario TOML) driving all four emulators, with ground truth", world_main);
