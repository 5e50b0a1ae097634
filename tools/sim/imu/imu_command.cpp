// `ugv-sim imu --pty PATH`: the 3DM-GX1 emulator on a pseudo-terminal. This file is only the
// I/O: the pty, the wall clock, pacing bytes at the line rate in randomly split writes, the
// baud check, and the fault schedule (including bit errors on the line). The device itself
// is Gx1Emulator.
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "imu_emulator.hpp"
#include "ugv/io/clock.hpp"
#include "ugv/io/pty.hpp"
#include "ugv/runtime/stop_signals.hpp"
#include "ugv/sim/command.hpp"
#include "ugv/sim/line_faults.hpp"
#include "ugv/sim/parse_command_line.hpp"

namespace {

using ugv::sim::imu::EmulatorConfig;
using ugv::sim::imu::Gx1Emulator;

constexpr double deg = 3.14159265358979323846 / 180.0;

double now_s() { return static_cast<double>(ugv::io::monotonic_us()) * 1e-6; }

struct Faults
{
    double garbage_every_s = 0;  // 0 = never
    int garbage_bytes = 16;
    double silence_after_s = 0;  // 0 = never
    double silence_for_s = 2;
    double disappear_after_s = 0;  // 0 = never: close the pty (an unplug)
    double gone_for_s = 0;         // 0 = stay gone (exit)
    double bit_error_rate = 0;     // per byte sent: one random bit flipped
    unsigned truncate_every = 0;   // every n-th streamed frame cut short (0 = never)
    unsigned truncate_replies = 0; // the first n command replies cut short
};

std::vector<uint16_t> parse_words(const std::string& text)
{
    std::vector<uint16_t> out;
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) out.push_back(static_cast<uint16_t>(std::stoul(item)));
    return out;
}

int imu_main(int argc, char** argv)
{
    CLI::App app{"MicroStrain 3DM-GX1 emulator on a pseudo-terminal", argv[0]};
    std::string pty_path, attitude = "level", timing = "16,16,256,1";
    int baud = 38400, command = 0x31;
    double roll_deg = 0, pitch_deg = 0, heading_deg = 0, yaw_rate_dps = 5, noise_deg = 0.05, accel_noise = 0.02,
           rate_noise = 0.002, duration_s = 0;
    bool streaming = false;
    EmulatorConfig cfg;
    Faults faults;
    app.add_option("--pty", pty_path, "symlink to create for the slave side")->required();
    app.add_option("--baud", baud, "the unit's line rate; other host rates get garbage")->capture_default_str();
    app.add_option("--rate", cfg.rate_hz, "continuous output rate (Hz), rounded to whole ticks")->capture_default_str();
    app.add_option("--timing", timing, "EEPROM timing words 238,240,242,246")->capture_default_str();
    app.add_option("--gyro-gain", cfg.gyro_gain_scale, "EEPROM 130")->capture_default_str();
    app.add_option("--accel-gain", cfg.accel_gain_scale, "EEPROM 230")->capture_default_str();
    app.add_option("--mag-gain", cfg.mag_gain_scale, "EEPROM 232")->capture_default_str();
    app.add_option("--serial", cfg.serial_number, "serial number (F1)")->capture_default_str();
    app.add_option("--clock-ppm", cfg.clock_ppm, "the unit's timer error")->capture_default_str();
    app.add_option("--attitude", attitude,
                   "level | slow-yaw | bench (the motions of tests/bench/imu-signs.sh, in a 20 s loop)")
        ->check(CLI::IsMember({"level", "slow-yaw", "bench"}))
        ->capture_default_str();
    app.add_option("--roll-deg", roll_deg, "NED roll (level mode)")->capture_default_str();
    app.add_option("--pitch-deg", pitch_deg, "NED pitch, nose up positive (level mode)")->capture_default_str();
    app.add_option("--heading-deg", heading_deg, "NED heading, clockwise from north (start heading)")->capture_default_str();
    app.add_option("--yaw-rate-dps", yaw_rate_dps, "slow-yaw turn rate, clockwise positive")->capture_default_str();
    app.add_option("--noise-deg", noise_deg, "1-sigma angle noise")->capture_default_str();
    app.add_option("--accel-noise", accel_noise, "1-sigma accel noise (m/s^2)")->capture_default_str();
    app.add_option("--rate-noise", rate_noise, "1-sigma rate noise (rad/s)")->capture_default_str();
    app.add_option("--seed", cfg.noise.seed, "noise and split seed")->capture_default_str();
    app.add_flag("--streaming", streaming, "power on streaming (as if left in continuous mode)");
    app.add_option("--streaming-command", command, "command streamed at power-on")->capture_default_str();
    app.add_option("--garbage-every", faults.garbage_every_s, "inject garbage every S seconds (0 = never)");
    app.add_option("--garbage-bytes", faults.garbage_bytes, "bytes per garbage burst")->capture_default_str();
    app.add_option("--silence-after", faults.silence_after_s, "go silent (hung unit) after S seconds (0 = never)");
    app.add_option("--silence-for", faults.silence_for_s, "silence length (s)")->capture_default_str();
    app.add_option("--disappear-after", faults.disappear_after_s, "close the pty (unplug) after S seconds (0 = never)");
    app.add_option("--gone-for", faults.gone_for_s, "re-create the pty after S seconds (0 = exit instead)");
    app.add_option("--bit-error-rate", faults.bit_error_rate, "per byte sent, flip one random bit with this probability")
        ->check(CLI::Range(0.0, 1.0));
    app.add_option("--truncate-every", faults.truncate_every, "cut every N-th streamed frame short (0 = never)");
    app.add_option("--truncate-replies", faults.truncate_replies,
                   "cut the first N replies to commands short (the host's handshake must retry)");
    app.add_option("--duration", duration_s, "exit after S seconds (0 = run until SIGTERM)");
    if (const auto status = ugv::sim::parse_command_line(app, argc, argv)) return *status;
    const auto timing_words = parse_words(timing);
    if (timing_words.size() != 4) {
        std::fprintf(stderr, "%s: --timing needs 4 words\n", argv[0]);
        return 2;
    }
    for (std::size_t i = 0; i < 4; ++i) cfg.timing.words[i] = timing_words[i];
    cfg.noise.angle_sigma_rad = noise_deg * deg;
    cfg.noise.accel_sigma_mps2 = accel_noise;
    cfg.noise.rate_sigma_radps = rate_noise;
    cfg.streaming_at_power_on = streaming;
    cfg.power_on_command = static_cast<uint8_t>(command);
    cfg.attitude = attitude == "level"  ? ugv::sim::imu::fixed_attitude(roll_deg * deg, pitch_deg * deg, heading_deg * deg)
                   : attitude == "bench" ? ugv::sim::imu::bench_motions(now_s(), heading_deg * deg)
                                         : ugv::sim::imu::slow_yaw(heading_deg * deg, yaw_rate_dps * deg);

    ugv::runtime::install_stop_signals();
    std::unique_ptr<ugv::io::Pty> pty;
    try {
        pty = std::make_unique<ugv::io::Pty>(pty_path);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", argv[0], e.what());
        return 1;
    }
    const double start_s = now_s();
    auto emu = std::make_unique<Gx1Emulator>(cfg, start_s);
    emu->set_truncate_every(faults.truncate_every);
    emu->set_truncate_replies(faults.truncate_replies);
    std::mt19937 line_rng(cfg.noise.seed + 2);  // bit errors on the line
    uint64_t bytes_damaged = 0;
    std::mt19937 split_rng(cfg.noise.seed + 1);
    std::uniform_int_distribution<int> garbage_byte(0, 255);
    const double byte_s = 10.0 / baud;
    double tx_free_s = start_s;  // when the line can carry the next byte
    double next_garbage_s = faults.garbage_every_s > 0 ? start_s + faults.garbage_every_s : INFINITY;
    bool gone = false, silenced = false;
    std::fprintf(stderr, "%s: 3DM-GX1 on %s (%s), %d baud\n", argv[0], pty->path().c_str(), pty->slave_path().c_str(), baud);

    std::vector<uint8_t> buf(256);
    while (!ugv::runtime::stop_requested()) {
        const double t = now_s();
        const double age = t - start_s;
        if (duration_s > 0 && age >= duration_s) break;
        if (faults.disappear_after_s > 0 && !gone && age >= faults.disappear_after_s) {
            std::fprintf(stderr, "%s: unplugged\n", argv[0]);
            pty.reset();
            gone = true;
            if (faults.gone_for_s <= 0) break;
        }
        if (gone) {
            if (age >= faults.disappear_after_s + faults.gone_for_s) {
                pty = std::make_unique<ugv::io::Pty>(pty_path);
                gone = false;
                faults.disappear_after_s = 0;
                emu = std::make_unique<Gx1Emulator>(cfg, t);  // plugged in = powered on again
                emu->set_truncate_every(faults.truncate_every);
                silenced = false;
                std::fprintf(stderr, "%s: plugged in again\n", argv[0]);
            } else {
                ::usleep(10000);
                continue;
            }
        }
        const bool want_silence = faults.silence_after_s > 0 && age >= faults.silence_after_s &&
                                  age < faults.silence_after_s + faults.silence_for_s;
        if (want_silence != silenced) {
            emu->set_silent(want_silence);
            silenced = want_silence;
        }
        if (t >= next_garbage_s) {
            emu->inject_garbage(static_cast<std::size_t>(faults.garbage_bytes));
            next_garbage_s += faults.garbage_every_s;
        }

        // Host -> unit. A host on another baud rate is heard as noise: ignored.
        const bool baud_ok = pty->slave_baud() == baud;
        pollfd pfd{pty->master_fd(), POLLIN, 0};
        const double next_event = std::min({emu->next_frame_s(), emu->output().empty() ? INFINITY : tx_free_s + byte_s,
                                            next_garbage_s, t + 0.02});
        const int timeout_ms = std::max(0, static_cast<int>(std::ceil((next_event - t) * 1000.0)));
        if (::poll(&pfd, 1, timeout_ms) > 0 && (pfd.revents & POLLIN)) {
            const ssize_t n = ::read(pty->master_fd(), buf.data(), buf.size());
            if (n > 0 && baud_ok) emu->receive(buf.data(), static_cast<std::size_t>(n), now_s());
        }
        const double t2 = now_s();
        emu->advance(t2);

        // Unit -> host, paced at the line rate, in random pieces.
        auto& out = emu->output();
        if (out.empty()) {
            tx_free_s = std::max(tx_free_s, t2);
            continue;
        }
        tx_free_s = std::max(tx_free_s, t2 - 0.05);  // never "owe" more than 50 ms of bytes
        const auto due = static_cast<std::size_t>(std::max(0.0, std::floor((t2 - tx_free_s) / byte_s)));
        const std::size_t n = ugv::sim::imu::random_chunk_size(split_rng, std::min(due, out.size()));
        if (n == 0) continue;
        std::vector<uint8_t> chunk(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(n));
        if (!baud_ok)
            for (auto& b : chunk) b = static_cast<uint8_t>(garbage_byte(split_rng));  // a rate mismatch
        bytes_damaged += ugv::sim::flip_bits(chunk.begin(), chunk.end(), faults.bit_error_rate, line_rng);
        const ssize_t w = ::write(pty->master_fd(), chunk.data(), chunk.size());
        if (w > 0) {
            out.erase(out.begin(), out.begin() + w);
            tx_free_s += static_cast<double>(w) * byte_s;
        }
    }
    std::fprintf(stderr, "%s: frames streamed %llu, truncated %llu; replies truncated %llu; bytes with a bit flipped %llu\n",
                 argv[0], static_cast<unsigned long long>(emu->counters().frames_streamed),
                 static_cast<unsigned long long>(emu->counters().frames_truncated),
                 static_cast<unsigned long long>(emu->counters().replies_truncated),
                 static_cast<unsigned long long>(bytes_damaged));
    return 0;
}

}  // namespace

UGV_SIM_COMMAND("imu", "MicroStrain 3DM-GX1 IMU on a pseudo-terminal", imu_main);
