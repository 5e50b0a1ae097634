// The LMS 2xx device session, written against ugv::io::ByteStream: finds the device at
// whatever rate it was left (probing 9600 -> 19200 -> 38400 -> 500000), switches it to the
// configured rate, stops streaming before reconfiguring, sets the variant, measuring mode
// and units, starts streaming, and turns scan telegrams into time-stamped scans. Every
// request has a timeout and retries; silence for several scan periods or repeated NAKs send
// it back to probing on the same open port (a device that restarted streams only when
// asked again); only a device that is gone (the stream says `closed`: EIO, hang-up, node
// vanished or replaced) is reopened. Never out of run().
//
// Threads: run() blocks on the calling thread (a daemon's device thread). stats() may be
// read from any thread.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "ugv/io/byte_stream.hpp"
#include "ugv/io/periodic_clock.hpp"
#include "ugv/sick_lms2xx/decoder.hpp"
#include "ugv/sick_lms2xx/replies.hpp"
#include "ugv/sick_lms2xx/scan.hpp"
#include "ugv/sick_lms2xx/timing.hpp"

namespace ugv::sick_lms2xx {

struct SessionConfig
{
    int baud = 500000;             // 9600, 19200, 38400 or 500000
    int angle_deg = 180;           // 100 or 180
    int resolution_cdeg = 50;      // 25 (100 deg only), 50 or 100
    Units units = Units::mm;       // mm: 8 m range; cm: 80 m
    bool scan_index = false;       // ask for the real-time scan index (availability 0x02)
    std::string password = "SICK_LMS";
    bool stop_on_exit = true;      // send `20 25` when run() ends
    int reply_timeout_ms = 300;    // per attempt
    int attempts = 3;              // per request (probes use 2)
    int settle_ms = 300;           // quiet time after a baud change
    int silence_periods = 5;       // scan intervals without a scan before re-initialising
    BeamTiming beam_timing = BeamTiming::interlaced;  // how beam times are modelled (timing.hpp)
    std::string sweep_order;       // phase measured by each sweep ("" = natural); see timing.hpp
    int64_t backoff_initial_us = 100'000;
    int64_t backoff_max_us = 2'000'000;
};
// Throws std::invalid_argument naming the first invalid field.
void validate(const SessionConfig& c);

enum class SessionState { probing, configuring, streaming, recovering, stopped };
const char* to_string(SessionState s);

// A decoded scan with its time stamps and geometry.
struct StampedScan
{
    Scan scan;
    int64_t arrival_utime = 0;     // when the telegram's last byte arrived (unfiltered)
    int64_t first_beam_utime = 0;  // start of the first sweep; see timing.hpp
    double time_increment_s = 0.0;
    double sweep_period_s = 0.0;
    SweepOrder sweep_order;        // beam i: first_beam + sweep(i) * sweep_period + i * time_increment
    double scan_period_s = 0.0;
    double angle_min_rad = 0.0;
    double angle_increment_rad = 0.0;
    double range_max_m = 0.0;
};

struct SessionStats
{
    std::atomic<int64_t> scans{0};
    std::atomic<int64_t> crc_errors{0};
    std::atomic<int64_t> resyncs{0};
    std::atomic<int64_t> naks{0};
    std::atomic<int64_t> timeouts{0};     // requests unanswered and scan silences
    std::atomic<int64_t> reconnects{0};   // times streaming was lost and recovery started
    std::atomic<int64_t> silences{0};     // scan silences (the port stays open: re-initialised on it)
    std::atomic<int64_t> reopens{0};      // the port closed and opened again: the device was gone
    std::atomic<int64_t> bytes_in{0};
    std::atomic<int64_t> bad_scans{0};    // good CRC but undecodable or wrong value count
    std::atomic<int64_t> clock_restarts{0};  // scan clock restarts (see ugv/io/periodic_clock.hpp)

    template <class F>
    void visit(F&& f) const
    {
        f("scans", scans.load());
        f("crc_errors", crc_errors.load());
        f("resyncs", resyncs.load());
        f("naks", naks.load());
        f("timeouts", timeouts.load());
        f("reconnects", reconnects.load());
        f("silences", silences.load());
        f("reopens", reopens.load());
        f("bytes_in", bytes_in.load());
        f("bad_scans", bad_scans.load());
        f("clock_restarts", clock_restarts.load());
    }
};

struct SessionCallbacks
{
    std::function<void(const StampedScan&)> on_scan;
    std::function<void(SessionState, const std::string& why)> on_state;
    // Every chunk read (from_device) or written, with its time: for raw captures.
    std::function<void(const uint8_t*, std::size_t, int64_t utime, bool from_device)> on_bytes;
    // The stream reported the device gone: reopen it. False = not there (yet).
    std::function<bool()> reopen;
    std::function<bool()> stop_requested;
    // Clocks and sleep, replaceable so tests can run in simulated time.
    std::function<int64_t()> monotonic_us;
    std::function<void(int64_t)> sleep_us;
};

class Session
{
public:
    Session(io::ByteStream& stream, SessionConfig config, SessionCallbacks callbacks);

    // Probes, configures and starts streaming. False (with last_error()) on failure.
    bool initialise();
    enum class PumpResult { ok, silence, closed, stopped };
    // Reads what arrives within timeout_ms and delivers the scans in it.
    PumpResult pump(int timeout_ms);
    // initialise + pump until stop_requested(), recovering from every failure; then
    // shutdown(). Starts by reopening when the stream is marked closed.
    void run();
    // Stops streaming if configured and the device is there.
    void shutdown();
    // Marks the stream as gone (e.g. the first open failed): run() reopens first.
    void mark_closed() { closed_ = true; }

    const SessionStats& stats() const { return stats_; }
    SessionState state() const { return state_; }
    const std::string& last_error() const { return error_; }
    const std::string& device_type() const { return device_type_; }
    // From the last handshake: 200/211/220/221/291 (model.hpp; 0 = a type string not known),
    // the status block's software version, the configuration block's length.
    int device_model() const { return device_model_; }
    const std::string& software_version() const { return software_version_; }
    std::size_t config_block_bytes() const { return config_block_bytes_; }
    int device_baud() const { return device_baud_; }
    // Seconds without a scan after which the session re-initialises.
    double silence_timeout_s() const;

private:
    int64_t now_us() const;
    void sleep(int64_t us);
    bool stopping() const;
    void set_state(SessionState s, const std::string& why = "");
    bool fail(const std::string& why);
    // Reads once (up to timeout_ms) and feeds the decoder.
    io::ReadResult::Status read_some(int timeout_ms);
    void on_event(const DecoderEvent& ev);
    void handle_scan(const Telegram& t);
    void sync_decoder_stats();
    // Telegrams that never became a scan: CRC and length errors, and undecodable scans.
    uint64_t rejected_telegrams() const;
    bool write(const std::vector<uint8_t>& bytes);
    // Sends request and waits for ACK + the reply with reply_cmd; reply_ holds its data.
    bool transact(const std::vector<uint8_t>& request, uint8_t reply_cmd, int attempts, const char* what);
    bool mode_switch(const std::vector<uint8_t>& request, const char* what);
    bool probe(int baud);
    bool switch_baud(int baud);
    bool configure();
    void settle(int ms);

    io::ByteStream& stream_;
    SessionConfig config_;
    SessionCallbacks cb_;
    Decoder decoder_;
    SessionStats stats_;
    SessionState state_ = SessionState::stopped;
    std::string error_, device_type_, software_version_;
    int device_model_ = 0;
    std::size_t config_block_bytes_ = 0;
    int device_baud_ = 0;
    bool closed_ = false;
    bool streaming_ = false;
    int64_t last_scan_us_ = 0;
    int expected_beams_ = 0;
    SweepOrder sweep_order_;
    // What transact() is waiting for.
    int awaiting_cmd_ = -1;
    bool got_ack_ = false, got_nak_ = false, got_reply_ = false, got_telegram_ = false;
    std::vector<uint8_t> reply_;  // data of the awaited reply (after CMD, without STATUS)
    int64_t chunk_utime_ = 0;
    io::PeriodicClock scan_clock_{0.0};  // set up for the configured resolution when streaming starts
    uint64_t rejected_at_last_scan_ = 0;  // rejected_telegrams() at the last good scan
    StampedScan scan_;
    std::vector<uint8_t> rx_;
};

}  // namespace ugv::sick_lms2xx
