// ugv-sim servo --pty PATH [--node-id N] ...: the emulated drive and slcan adapter served on
// a pseudo-terminal. Only the I/O and the CLI live here; the logic is DriveEmulator
// (servo_emulator.hpp) and SlcanAdapter.
//   SIGUSR1 raises a fault (EMCY 0x8611 following error); SIGUSR2 drops the node off the bus
//   for --loss-duration seconds (its heartbeat stops); SIGHUP puts the adapter's controller
//   bus-off (BEL, then silence until the host closes and reopens). --fault-after/--loss-after schedule
//   the same from the time the drive was first enabled. Line faults (serial_line_faults.hpp)
//   corrupt what the adapter sends; --bus-bitrate, --refuse-tx-every and --serial-baud are the
//   adapter's.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <cstdint>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <cstdlib>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "serial_line_faults.hpp"
#include "servo_emulator.hpp"
#include "slcan_adapter.hpp"
#include "ugv/io/clock.hpp"
#include "ugv/io/pty.hpp"
#include "ugv/io/slcan_codec.hpp"
#include "ugv/runtime/stop_signals.hpp"
#include "ugv/sim/command.hpp"
#include "ugv/sim/parse_command_line.hpp"

namespace {

// The fault signals stay this command's own; SIGINT/SIGTERM are the shared stop signals.
std::atomic<int> g_faults{0};
std::atomic<int> g_losses{0};
std::atomic<int> g_bus_offs{0};

void on_fault_signal(int sig)
{
    if (sig == SIGUSR1) g_faults.fetch_add(1);
    else if (sig == SIGUSR2) g_losses.fetch_add(1);
    else if (sig == SIGHUP) g_bus_offs.fetch_add(1);
}

// Writes what the host will take within ~10 ms; the rest is dropped (returned false), as a
// USB adapter drops frames when the host stops reading, so the emulator never blocks.
bool write_some(int fd, const std::string& s)
{
    std::size_t off = 0;
    int waits = 0;
    while (off < s.size()) {
        const ssize_t n = ::write(fd, s.data() + off, s.size() - off);
        if (n >= 0) {
            off += static_cast<std::size_t>(n);
            continue;
        }
        if (errno == EINTR) continue;
        if (errno != EAGAIN || ++waits > 10) return false;
        pollfd p{fd, POLLOUT, 0};
        ::poll(&p, 1, 1);
    }
    return true;
}

int servo_main(int argc, char** argv)
{
    CLI::App app{"A CiA 402 servo drive behind an slcan adapter on a pseudo-terminal", argv[0]};
    std::string pty_path;
    int node = 1;
    double initial_deg = 0.0, counts_per_rad = 4096.0 * 50.0 / (2.0 * M_PI);
    double fault_after = -1.0, loss_after = -1.0, loss_duration = 1.0;
    double garbage_every_s = 0.0;
    int bus_bitrate = 0, serial_baud = 0;
    unsigned refuse_tx_every = 0;
    ugv::sim::servo::SerialLineFaultConfig line_faults;
    line_faults.garbage_bytes = 16;
    ugv::sim::servo::DriveShape shape;
    std::vector<std::string> removed;
    app.add_option("--pty", pty_path, "symlink to create for the adapter's serial port")->required();
    app.add_option("--node-id", node, "the drive's CANopen node id")->check(CLI::Range(1, 127))->capture_default_str();
    app.add_option("--initial-deg", initial_deg, "the axis at power-on (deg)")->capture_default_str();
    app.add_option("--counts-per-rad", counts_per_rad, "encoder counts per radian of the axis")->capture_default_str();
    app.add_option("--fault-after", fault_after, "raise the fault S seconds after the drive was first enabled (< 0: never)")
        ->capture_default_str();
    app.add_option("--loss-after", loss_after, "drop off the bus S seconds after the drive was first enabled (< 0: never)")
        ->capture_default_str();
    app.add_option("--loss-duration", loss_duration, "how long a drop off the bus lasts (s)")->capture_default_str();
    app.add_option("--bit-error-rate", line_faults.bit_error_rate, "per byte the adapter sends, one random bit flipped")
        ->check(CLI::Range(0.0, 1.0));
    app.add_option("--truncate-every", line_faults.truncate_every, "every N-th frame line cut short before its CR (0 = never)");
    app.add_option("--garbage-every", garbage_every_s, "--garbage-bytes random bytes between lines every S seconds (0 = never)");
    app.add_option("--garbage-bytes", line_faults.garbage_bytes, "bytes per garbage burst")->capture_default_str();
    app.add_option("--seed", line_faults.seed, "seed of the line faults")->capture_default_str();
    app.add_option("--bus-bitrate", bus_bitrate, "the bus runs at B bit/s: nothing passes unless the host set B (0 = any)");
    app.add_option("--refuse-tx-every", refuse_tx_every, "every N-th transmit answered BEL (0 = never)");
    app.add_option("--serial-baud", serial_baud, "the adapter's serial side runs at B: a host at another rate is not "
                                                 "understood and hears noise (0 = any)")
        ->check(CLI::NonNegativeNumber);
    app.add_option("--tpdos", shape.tpdos, "TPDOs the drive has (the others answer 0x06020000)")
        ->check(CLI::Range(1, 4))->capture_default_str();
    app.add_option("--rpdos", shape.rpdos, "RPDOs the drive has")->check(CLI::Range(1, 4))->capture_default_str();
    app.add_flag("--fixed-mapping", shape.fixed_mapping,
                 "PDO mappings are read-only (0x06010002): TPDO1 statusword + position, TPDO2 statusword + velocity, "
                 "TPDO3 position + velocity, TPDO4 error code; RPDO1 controlword + target, RPDO2 controlword + mode, "
                 "RPDO3 profile velocity, RPDO4 acceleration + deceleration");
    app.add_option("--max-mapped", shape.max_mapped, "objects a PDO can map (its mapping sub-indices)")
        ->check(CLI::Range(1, 8))->capture_default_str();
    app.add_flag("--no-heartbeat", [&](std::int64_t) { shape.heartbeat = false; },
                 "no heartbeat producer: 0x1017 answers 0x06020000 (the boot-up message is still sent)");
    app.add_flag("--sync-only", shape.sync_only,
                 "TPDOs only on SYNC: no event timer (sub 5 absent), transmission types 0xFE/0xFF refused (0x06090030)");
    app.add_option("--remove-object", removed, "a CiA 402 object the drive lacks, e.g. 0x606C (repeatable)");
    app.footer("Signals: SIGUSR1 raises a fault (EMCY 0x8611 following error). SIGUSR2 drops the node off the bus\n"
               "for --loss-duration s. SIGHUP puts the adapter's controller bus-off (BEL; silent until the host\n"
               "closes and reopens). SIGINT/SIGTERM stop.");
    if (const auto status = ugv::sim::parse_command_line(app, argc, argv)) return *status;
    const auto bus_bitrate_command = ugv::io::slcan::encode_bitrate(bus_bitrate);
    for (const auto& r : removed) {
        char* end = nullptr;
        const unsigned long index = std::strtoul(r.c_str(), &end, 0);
        if (end == r.c_str() || *end != '\0' || index < 0x6000 || index > 0x67FF) {
            std::fprintf(stderr, "%s: --remove-object %s: not a CiA 402 object index (0x6000 ... 0x67FF)\n", argv[0],
                         r.c_str());
            return 2;
        }
        shape.removed.push_back(static_cast<uint16_t>(index));
    }
    if (pty_path.empty()) {
        std::fprintf(stderr, "%s: --pty: an empty path\n", argv[0]);
        return 2;
    }
    if (bus_bitrate != 0 && !bus_bitrate_command) {
        std::fprintf(stderr, "%s: --bus-bitrate %d: not a CAN rate an slcan adapter sets (10000 ... 1000000)\n", argv[0],
                     bus_bitrate);
        return 2;
    }

    ugv::runtime::install_stop_signals();
    struct sigaction sa{};
    sa.sa_handler = on_fault_signal;
    sigemptyset(&sa.sa_mask);
    for (int sig : {SIGUSR1, SIGUSR2, SIGHUP}) sigaction(sig, &sa, nullptr);

    ugv::io::Pty pty(pty_path);
    ::fcntl(pty.master_fd(), F_SETFL, ::fcntl(pty.master_fd(), F_GETFL) | O_NONBLOCK);
    ugv::sim::servo::DriveModel model;
    model.node_id = static_cast<uint8_t>(node);
    model.initial_position_counts = initial_deg * M_PI / 180.0 * counts_per_rad;
    model.shape = shape;
    ugv::sim::servo::DriveEmulator drive(model);
    ugv::sim::servo::SlcanAdapter adapter;
    if (bus_bitrate_command) adapter.set_bus_bitrate_code((*bus_bitrate_command)[1] - '0');
    adapter.set_refuse_tx_every(refuse_tx_every);
    ugv::sim::servo::SerialLineFaults serial_line(line_faults);
    std::fprintf(stderr, "ugv-sim servo: node %d on %s (slave %s)\n", node, pty.path().c_str(), pty.slave_path().c_str());

    const int64_t t0 = ugv::io::monotonic_us();
    drive.power_on(t0);
    int64_t enabled_at = -1;
    int64_t next_garbage_us = garbage_every_s > 0 ? t0 + static_cast<int64_t>(garbage_every_s * 1e6) : INT64_MAX;
    bool fault_done = false, loss_done = false;
    int faults_seen = 0, losses_seen = 0, bus_offs_seen = 0;
    uint64_t dropped_writes = 0;
    std::mt19937 noise(line_faults.seed);
    while (!ugv::runtime::stop_requested()) {
        // A host at another serial rate samples the wrong bit cells both ways.
        const bool rate_matches = serial_baud == 0 || pty.slave_baud() == serial_baud;
        pollfd p{pty.master_fd(), POLLIN, 0};
        const int rc = ::poll(&p, 1, 1);
        const int64_t now = ugv::io::monotonic_us();
        if (rc > 0 && (p.revents & POLLIN)) {
            uint8_t buf[1024];
            const ssize_t n = ::read(pty.master_fd(), buf, sizeof buf);
            if (n > 0 && rate_matches) {
                for (const auto& f : adapter.feed(buf, static_cast<std::size_t>(n), now)) drive.on_frame(f, now);
            }
        }
        drive.advance(now);
        if (enabled_at < 0 && drive.state() == ugv::canopen::cia402::State::operation_enabled) enabled_at = now;
        const double since = enabled_at < 0 ? -1.0 : static_cast<double>(now - enabled_at) * 1e-6;
        if (g_faults.load() > faults_seen || (!fault_done && fault_after >= 0 && since >= fault_after)) {
            faults_seen = g_faults.load();
            fault_done = fault_done || (fault_after >= 0 && since >= fault_after);
            std::fprintf(stderr, "ugv-sim servo: raising fault 0x8611 (following error)\n");
            drive.raise_fault(0x8611, now);
        }
        if (g_losses.load() > losses_seen || (!loss_done && loss_after >= 0 && since >= loss_after)) {
            losses_seen = g_losses.load();
            loss_done = loss_done || (loss_after >= 0 && since >= loss_after);
            std::fprintf(stderr, "ugv-sim servo: dropping off the bus for %.1f s\n", loss_duration);
            drive.drop_off_bus(static_cast<int64_t>(loss_duration * 1e6), now);
        }
        if (g_bus_offs.load() > bus_offs_seen) {
            bus_offs_seen = g_bus_offs.load();
            std::fprintf(stderr, "ugv-sim servo: adapter bus-off\n");
            adapter.bus_off();
        }
        for (const auto& f : drive.take_outgoing()) adapter.on_bus_frame(f, now);
        const bool garbage_now = now >= next_garbage_us;
        if (garbage_now) next_garbage_us += static_cast<int64_t>(garbage_every_s * 1e6);
        std::string out = serial_line.apply(adapter.take_output(), garbage_now);
        if (!rate_matches) {
            for (auto& c : out) c = static_cast<char>(noise() & 0xFFU);
            out.resize(out.size() / 2);
        }
        if (!out.empty() && !write_some(pty.master_fd(), out) && ++dropped_writes % 1000 == 1) {
            std::fprintf(stderr, "ugv-sim servo: the host is not reading; output dropped (%llu times)\n",
                         static_cast<unsigned long long>(dropped_writes));
        }
    }
    std::fprintf(stderr,
                 "ugv-sim servo: bytes with a bit flipped %llu, lines truncated %llu, garbage bytes %llu, transmits refused %llu\n",
                 static_cast<unsigned long long>(serial_line.bytes_damaged()),
                 static_cast<unsigned long long>(serial_line.lines_truncated()),
                 static_cast<unsigned long long>(serial_line.garbage_sent()),
                 static_cast<unsigned long long>(adapter.tx_refused()));
    return 0;
}

}  // namespace

UGV_SIM_COMMAND("servo", "CiA 402 servo drive behind an slcan adapter on a pseudo-terminal", servo_main);
