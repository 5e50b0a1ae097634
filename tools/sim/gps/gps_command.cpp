// ugv-sim gps: the NovAtel receiver emulator on a pseudo-terminal. The receiver logic is
// GpsEmulator (no I/O); this file is the pty, the clock, the baud check and the unplug fault.
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <memory>
#include <random>
#include <string>
#include <thread>

#include <CLI/CLI.hpp>

#include "gps_emulator.hpp"
#include "ugv/io/clock.hpp"
#include "ugv/io/pty.hpp"
#include "ugv/runtime/stop_signals.hpp"
#include "ugv/sim/command.hpp"
#include "ugv/sim/parse_command_line.hpp"

namespace {

// Writes what the slave side can take; a full line drops the rest, as a UART would.
void write_some(int fd, const std::string& bytes)
{
    std::size_t done = 0;
    while (done < bytes.size()) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n <= 0) {
            return;
        }
        done += static_cast<std::size_t>(n);
    }
}

// What the host sees when its baud differs from the receiver's: bytes, but not these.
std::string garble(const std::string& bytes, std::mt19937& rng)
{
    std::string out = bytes;
    for (auto& c : out) {
        c = static_cast<char>(rng() & 0xFFU);
    }
    return out.substr(0, out.size() / 2 + 1);
}

int gps_main(int argc, char** argv)
{
    using ugv::sim::gps::EmulatorConfig;
    using ugv::sim::gps::Protocol;
    CLI::App app{"NovAtel OEM4-class GPS receiver emulator on a pseudo-terminal", argv[0]};
    std::string pty_path, protocol = "novatel", script = "SINGLE@0";
    EmulatorConfig cfg;
    double unplug_at_s = -1, unplug_for_s = 1.0, duration_s = 0;
    app.add_option("--pty", pty_path, "symlink to create for the receiver's port")->required();
    app.add_option("--protocol", protocol, "novatel | nmea")->check(CLI::IsMember({"novatel", "nmea"}));
    app.add_option("--baud", cfg.baud, "the receiver port's rate at power-up");
    app.add_option("--lat", cfg.latitude_deg, "start latitude (deg)");
    app.add_option("--lon", cfg.longitude_deg, "start longitude (deg)");
    app.add_option("--height", cfg.height_msl_m, "height above MSL (m)");
    app.add_option("--undulation", cfg.undulation_m, "geoid undulation (m)");
    app.add_option("--speed", cfg.speed_mps, "speed along a straight line (m/s), 0 = stationary");
    app.add_option("--heading", cfg.heading_deg, "heading of the line (deg from north)");
    app.add_option("--noise", cfg.noise_scale, "position noise, x the position type's sigma (0 = none)");
    app.add_option("--seed", cfg.seed, "noise seed");
    app.add_option("--fix-script", script, "position types over time, e.g. SINGLE@0,PSRDIFF@5,NARROW_INT@10");
    app.add_flag("--preconfigured", cfg.preconfigured, "logs already running at power-up (for passive hosts)");
    app.add_option("--rate-hz", cfg.rate_hz, "rate of the preconfigured logs")->check(CLI::Range(0.05, 20.0));
    app.add_option("--leap-seconds", cfg.leap_seconds, "GPS - UTC (s)");
    app.add_option("--garbage-period", cfg.garbage_period_s, "a burst of random bytes every S seconds");
    app.add_option("--silence-at", cfg.silence_at_s, "stop sending at S seconds after start ...");
    app.add_option("--silence-for", cfg.silence_for_s, "... for S seconds");
    app.add_option("--bit-error-rate", cfg.bit_error_rate, "one bit flipped in each byte sent with probability P")
        ->check(CLI::Range(0.0, 1.0));
    app.add_option("--truncate-probability", cfg.truncate_probability,
                   "a log frame cut short (first 1..size-1 bytes only) with probability P")
        ->check(CLI::Range(0.0, 1.0));
    app.add_option("--unplug-at", unplug_at_s, "remove the port at S seconds after start ...");
    app.add_option("--unplug-for", unplug_for_s, "... and plug it back after S seconds");
    app.add_option("--duration", duration_s, "exit after S seconds (0 = until SIGTERM)");
    if (const auto status = ugv::sim::parse_command_line(app, argc, argv)) return *status;
    cfg.protocol = protocol == "nmea" ? Protocol::nmea : Protocol::novatel;
    try {
        cfg.script = ugv::sim::gps::parse_script(script);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: --fix-script: %s\n", argv[0], e.what());
        return 2;
    }
    ugv::runtime::install_stop_signals();

    auto pty = std::make_unique<ugv::io::Pty>(pty_path);
    const int64_t start = ugv::io::now_utime();
    ugv::sim::gps::GpsEmulator emulator(cfg, start);
    std::mt19937 rng(cfg.seed);
    std::fprintf(stderr, "%s: %s receiver on %s (%s), %d baud\n", argv[0], protocol.c_str(), pty_path.c_str(),
                 pty->slave_path().c_str(), cfg.baud);
    bool unplugged_done = false;
    uint8_t buf[512];
    while (!ugv::runtime::stop_requested()) {
        const int64_t now = ugv::io::now_utime();
        const double elapsed = static_cast<double>(now - start) * 1e-6;
        if (duration_s > 0 && elapsed >= duration_s) {
            break;
        }
        if (unplug_at_s >= 0 && !unplugged_done && elapsed >= unplug_at_s) {
            std::fprintf(stderr, "%s: unplugged for %.1f s\n", argv[0], unplug_for_s);
            pty->close();
            std::this_thread::sleep_for(std::chrono::duration<double>(unplug_for_s));
            pty = std::make_unique<ugv::io::Pty>(pty_path);
            unplugged_done = true;
            std::fprintf(stderr, "%s: plugged back in (%s)\n", argv[0], pty->slave_path().c_str());
            continue;
        }
        pollfd pfd{pty->master_fd(), POLLIN, 0};
        ::poll(&pfd, 1, 5);
        const bool baud_matches = pty->slave_baud() == emulator.baud();
        if (pfd.revents & POLLIN) {
            const ssize_t n = ::read(pty->master_fd(), buf, sizeof buf);
            if (n > 0 && baud_matches) {
                // The reply goes out at the current rate even when it is a COM change.
                write_some(pty->master_fd(), emulator.on_host_bytes(buf, static_cast<std::size_t>(n)));
            }
        }
        const std::string out = emulator.tick(ugv::io::now_utime());
        if (!out.empty()) {
            write_some(pty->master_fd(), baud_matches ? out : garble(out, rng));
        }
    }
    std::fprintf(stderr, "%s: commands %llu, bit errors %llu bytes, truncated %llu frames, %llu NMEA sentences damaged unseen\n", argv[0],
                 static_cast<unsigned long long>(emulator.commands_received()),
                 static_cast<unsigned long long>(emulator.bytes_damaged()),
                 static_cast<unsigned long long>(emulator.frames_truncated()),
                 static_cast<unsigned long long>(emulator.nmea_damage_unseen()));
    return 0;
}

}  // namespace

UGV_SIM_COMMAND("gps", "NovAtel OEM4 / Sokkia GSR2600 GPS receiver (binary, ASCII, NMEA) on a pseudo-terminal",
                gps_main);
