// The SICK LMS 2xx as seen from its serial port, without any I/O: bytes from the host go in
// (with the line rate the host has set), the device's bytes come out. ugv-sim lms wraps it
// around a pseudo-terminal; tests drive it directly.
//
// What it models: ACK then reply for every request; NAK for a bad CRC or an unknown request;
// a wrong password refused (0xA0 code 0x01); a variant change refused while streaming;
// configuration writes only in installation mode; the baud rate (a host at another rate
// sends the device garbage and receives garbage); a baud switch taking effect after its
// reply; scans streamed at the real period (26.67 ms at 180/0.5), skipped while the line is
// still busy with the previous one (so 0.5 deg at 38400 gives about 5 Hz, as on the real
// device); the variants (lms_variants.hpp); and injected faults.
#pragma once

#include <cstdint>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "lms_variants.hpp"
#include "ugv/sick_lms2xx/decoder.hpp"
#include "ugv/sick_lms2xx/scan.hpp"

namespace ugv::sim::lms {

struct Faults
{
    double garbage_probability = 0.0;  // per telegram sent: 1-40 random bytes before it
    double bitflip_probability = 0.0;  // per scan sent: one bit flipped
    double silence_every_s = 0.0;      // > 0: every this many seconds ...
    double silence_for_s = 0.0;        // ... the device sends nothing for this long
    double bit_error_rate = 0.0;       // per byte sent (replies, NAKs, scans): one bit flipped
    double truncate_probability = 0.0; // per scan: only its first 1..size-1 bytes are sent
};

// The range in metres seen along a beam at angle_rad (0 = straight ahead, counter-clockwise
// positive); NaN or infinity = no echo.
using Scene = std::function<double(double angle_rad)>;

// A flat floor seen from height_m, the scan plane pitched down by pitch_rad.
Scene flat_floor_scene(double height_m, double pitch_rad);

// A scene that moves (ugv-sim world): the range along the beam at angle_rad measured at
// beam_utime. Asked for every beam of every scan, in beam order (not time order when the
// scan is interlaced); the beam times follow the mirror (DeviceOptions::linear_timing).
using BeamScene = std::function<double(double angle_rad, int64_t beam_utime)>;

struct DeviceOptions
{
    Scene scene;
    BeamScene beam_scene;  // when set, used instead of scene
    Faults faults;
    uint32_t seed = 1;
    int initial_baud = 9600;
    bool initially_streaming = false;  // a device left streaming by a crashed host
    Variant variant = variants().front();  // what it answers to 3A/31/74 (lms_variants.hpp)
    std::string password = "SICK_LMS";
    // Beam times. The mirror turns at 75 Hz and crosses the field in the first part of each
    // turn (angle x 13.33 ms / 360 deg); at 0.5 deg a scan is 2 sweeps, at 0.25 deg 4, sweep
    // k measuring the beams i with i mod S = order[k]. The scan is sent when its last beam is
    // measured. linear_timing instead spreads the beams in angle order over the whole scan
    // period, ending at the telegram (the model the driver used before; for comparison).
    bool linear_timing = false;
    std::vector<int> sweep_order_05{0, 1};
    std::vector<int> sweep_order_025{0, 1, 2, 3};
};
// Parses an order such as "10" or "2031" (a permutation of 0..n-1, n = 2 or 4) into
// options; false (options unchanged) if it is not one.
bool set_sweep_order(DeviceOptions& options, const std::string& digits);

struct DeviceStats
{
    uint64_t requests = 0;        // good request telegrams
    uint64_t naks = 0;            // NAK bytes sent
    uint64_t garbled_input = 0;   // host bytes received at a wrong baud (ignored)
    uint64_t scans_sent = 0;
    uint64_t scans_skipped = 0;   // due while the line was still busy, or over 1 s late
    uint64_t baud_switches = 0;
    uint64_t bytes_damaged = 0;   // bytes with a bit flipped by the bit error rate
    uint64_t scans_truncated = 0;
};

class LmsDevice
{
public:
    explicit LmsDevice(DeviceOptions options);

    // Bytes the host wrote while its line was set to host_baud. Output is appended to out.
    void receive(const uint8_t* data, std::size_t n, int host_baud, int64_t now_us, std::vector<uint8_t>& out);
    // Emits the scans due by now_us.
    void tick(int64_t now_us, int host_baud, std::vector<uint8_t>& out);
    // When tick() next has something to do (INT64_MAX when not streaming).
    int64_t next_event_us() const;

    int baud() const { return baud_; }
    bool streaming() const { return streaming_; }
    bool installation_mode() const { return installation_; }
    int angle_deg() const { return angle_deg_; }
    int resolution_cdeg() const { return resolution_cdeg_; }
    sick_lms2xx::Units units() const;
    const std::vector<uint8_t>& config_block() const { return config_; }
    const DeviceStats& stats() const { return stats_; }

private:
    void handle(const sick_lms2xx::Telegram& t, int64_t now_us, int host_baud, std::vector<uint8_t>& out);
    void handle_mode(const sick_lms2xx::Telegram& t, int64_t now_us, int host_baud, std::vector<uint8_t>& out);
    void reply(uint8_t command, const std::vector<uint8_t>& data, int64_t now_us, int host_baud, std::vector<uint8_t>& out);
    void nak(int host_baud, int64_t now_us, std::vector<uint8_t>& out);
    // Puts bytes on the line: as they are when the host's rate matches, garbage otherwise.
    void send(std::vector<uint8_t> bytes, int host_baud, int64_t now_us, std::vector<uint8_t>& out, bool is_telegram);
    bool silent(int64_t now_us) const;
    std::vector<uint8_t> make_scan(int64_t now_us);
    // When beam i of n was measured, for a scan whose last beam was measured at last_beam_us.
    double beam_time_us(int i, int n, double last_beam_us) const;
    // The scan that fell due at due_us, unless the line is still busy then.
    void send_scan(int64_t due_us, int host_baud, std::vector<uint8_t>& out);

    DeviceOptions options_;
    sick_lms2xx::Decoder decoder_{sick_lms2xx::kHostAddress};
    std::mt19937 rng_;
    int baud_;
    int pending_baud_ = 0;  // the rate to switch to once the current chunk is handled
    bool streaming_;
    bool installation_ = false;
    int angle_deg_ = 180;
    int resolution_cdeg_ = 50;
    std::vector<uint8_t> config_;
    int64_t next_scan_us_ = 0;
    int64_t line_free_us_ = 0;
    int64_t epoch_us_ = -1;  // first time seen, the origin of the silence windows
    uint32_t scan_counter_ = 0;
    std::vector<double> beam_ranges_;  // the scene sampled for the current variant
    DeviceStats stats_;
};

}  // namespace ugv::sim::lms
