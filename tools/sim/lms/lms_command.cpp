// ugv-sim lms: the LMS 2xx emulator on a pseudo-terminal. The device logic is LmsDevice; this
// file only moves bytes between it and the pty master, reads the line rate the host set on
// the slave, keeps time and plays the disappear fault.
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#include "fault_spec.hpp"
#include "lms_emulator.hpp"
#include "ugv/io/clock.hpp"
#include "ugv/io/pty.hpp"
#include "ugv/runtime/stop_signals.hpp"
#include "ugv/sim/command.hpp"
#include "ugv/sim/parse_command_line.hpp"

namespace {

using namespace ugv::sim::lms;

constexpr double kPi = 3.14159265358979323846;

struct Counters
{
    uint64_t written = 0;
    uint64_t dropped = 0;  // bytes the host did not take (pty buffer full)
};

void write_out(int fd, std::vector<uint8_t>& out, Counters& c)
{
    std::size_t at = 0;
    while (at < out.size()) {
        const ssize_t n = ::write(fd, out.data() + at, out.size() - at);
        if (n > 0) {
            at += static_cast<std::size_t>(n);
            continue;
        }
        if (n < 0 && errno == EINTR) continue;
        break;  // EAGAIN: nobody is reading; a real line would lose these bytes too
    }
    c.written += at;
    c.dropped += out.size() - at;
    out.clear();
}

// Serves one device on one pty until stop, or until the disappear fault ends its life.
// Returns false when it stopped for good.
bool serve(const std::string& path, const DeviceOptions& options, const FaultPlan& plan, bool verbose)
{
    ugv::io::Pty pty(path);
    std::fprintf(stderr, "ugv-sim lms: %s (%s) %s -> %s at %d baud%s\n", options.variant.name.c_str(),
                 options.variant.type_string.c_str(), pty.path().c_str(), pty.slave_path().c_str(), options.initial_baud,
                 options.initially_streaming ? ", streaming" : "");
    LmsDevice device(options);
    Counters counters;
    const int64_t born_us = ugv::io::monotonic_us();
    const int64_t die_us = plan.disappear_after_s > 0 ? born_us + static_cast<int64_t>(plan.disappear_after_s * 1e6) : INT64_MAX;
    std::vector<uint8_t> in(4096), out;
    int last_baud = -1, last_device_baud = device.baud();
    bool was_streaming = device.streaming();
    while (!ugv::runtime::stop_requested()) {
        int64_t now = ugv::io::monotonic_us();
        if (now >= die_us) {
            std::fprintf(stderr, "ugv-sim lms: fault: disappearing for %.1f s\n", plan.disappear_for_s);
            pty.close();
            return true;
        }
        const int64_t wait_us = std::clamp<int64_t>(std::min(device.next_event_us(), die_us) - now, 0, 20'000);
        pollfd p{pty.master_fd(), POLLIN, 0};
        const int ready = ::poll(&p, 1, static_cast<int>((wait_us + 999) / 1000));
        now = ugv::io::monotonic_us();
        const int host_baud = pty.slave_baud();
        if (verbose && host_baud != last_baud) std::fprintf(stderr, "ugv-sim lms: host line now %d baud\n", host_baud);
        last_baud = host_baud;
        if (ready > 0 && (p.revents & POLLIN) != 0) {
            const ssize_t n = ::read(pty.master_fd(), in.data(), in.size());
            if (n > 0) device.receive(in.data(), static_cast<std::size_t>(n), host_baud, now, out);
        }
        device.tick(now, host_baud, out);
        if (!out.empty()) write_out(pty.master_fd(), out, counters);
        if (device.baud() != last_device_baud) {
            std::fprintf(stderr, "ugv-sim lms: device now at %d baud\n", device.baud());
            last_device_baud = device.baud();
        }
        if (device.streaming() != was_streaming) {
            was_streaming = device.streaming();
            std::fprintf(stderr, "ugv-sim lms: streaming %s (%d deg / %.2f deg, %s)\n", was_streaming ? "on" : "off",
                         device.angle_deg(), device.resolution_cdeg() / 100.0,
                         device.units() == ugv::sick_lms2xx::Units::mm ? "mm" : "cm");
        }
    }
    const DeviceStats& s = device.stats();
    std::fprintf(stderr,
                 "ugv-sim lms: requests %llu, naks %llu, scans sent %llu, skipped %llu, truncated %llu, garbled input "
                 "%llu bytes, bit errors %llu bytes, bytes written %llu, dropped %llu\n",
                 static_cast<unsigned long long>(s.requests), static_cast<unsigned long long>(s.naks),
                 static_cast<unsigned long long>(s.scans_sent), static_cast<unsigned long long>(s.scans_skipped),
                 static_cast<unsigned long long>(s.scans_truncated), static_cast<unsigned long long>(s.garbled_input),
                 static_cast<unsigned long long>(s.bytes_damaged), static_cast<unsigned long long>(counters.written),
                 static_cast<unsigned long long>(counters.dropped));
    return false;
}

int lms_main(int argc, char** argv)
{
    CLI::App app{"SICK LMS 2xx emulator on a pseudo-terminal", argv[0]};
    std::string path;
    double height_m = 1.0, pitch_deg = 10.0;
    int baud = 9600;
    bool streaming = false, verbose = false;
    unsigned seed = 1;
    std::string password = "SICK_LMS";
    std::string variant = "LMS200";
    std::vector<std::string> faults;
    app.add_option("--pty", path, "symlink to create for the slave side (the daemon's device)")->required();
    app.add_option("--height", height_m, "scene: sensor height above the flat floor, m")->check(CLI::Range(0.05, 10.0));
    app.add_option("--pitch-deg", pitch_deg, "scene: scan plane pitched down by, deg")->check(CLI::Range(0.0, 90.0));
    app.add_option("--baud", baud, "line rate at power-on (a device left at another rate by a crashed host)")
        ->check(CLI::IsMember({9600, 19200, 38400, 500000}));
    app.add_flag("--streaming", streaming, "start streaming (a device left streaming)");
    app.add_option("--password", password, "installation-mode password");
    app.add_option("--variant", variant,
                   "the model it acts as: " + variant_names() + " (type string, status, configuration block; docs/lms.md)");
    app.add_option("--seed", seed, "random seed of the faults");
    app.add_option("--fault", faults,
                   "garbage[:P] | bitflip[:P] | ber[:P] | truncate[:P] | silence[:EVERY[:FOR]] | disappear[:AFTER[:GONE]] "
                   "(repeatable)");
    app.add_flag("-v,--verbose", verbose, "log the host's line rate changes");
    if (const auto status = ugv::sim::parse_command_line(app, argc, argv)) return *status;
    FaultPlan plan;
    try {
        for (const std::string& f : faults) add_fault(f, plan);
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "%s: %s\n", argv[0], e.what());
        return 2;
    }
    DeviceOptions options;
    try {
        options.variant = find_variant(variant);
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "%s: %s\n", argv[0], e.what());
        return 2;
    }
    options.scene = flat_floor_scene(height_m, pitch_deg * kPi / 180.0);
    options.faults = plan.device;
    options.seed = seed;
    options.initial_baud = baud;
    options.initially_streaming = streaming;
    options.password = password;

    ugv::runtime::install_stop_signals();
    try {
        while (serve(path, options, plan, verbose)) {
            // Unplugged: gone for a while, then a freshly powered device appears.
            const int64_t back = ugv::io::monotonic_us() + static_cast<int64_t>(plan.disappear_for_s * 1e6);
            while (!ugv::runtime::stop_requested() && ugv::io::monotonic_us() < back) std::this_thread::sleep_for(std::chrono::milliseconds(10));
            if (ugv::runtime::stop_requested()) break;
            options.initial_baud = 9600;
            options.initially_streaming = false;
            ++options.seed;
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", argv[0], e.what());
        return 1;
    }
    return 0;
}

}  // namespace

UGV_SIM_COMMAND("lms", "SICK LMS 2xx laser on a pseudo-terminal (RS-422, 9600-500000 baud)", lms_main);
