// The 3DM-GX1 device session on a ugv::io::ByteStream: handshake, streaming (continuous mode)
// or polling, time stamps, timeouts and recovery. No threads, no LCM: the caller loops on
// step() and publishes what it gets.
//
// initialise():
//   1. stop continuous mode (the unit may have been left streaming), let the line settle
//      and flush what is still arriving;
//   2. read firmware version (F0) and serial number (F1);
//   3. read the per-unit gains (EEPROM 130, 230, 232) and the timing words (238, 240, 242,
//      246) that define the timer tick;
//   4. continuous: send `10 00 <command>` and wait for the echo or the first frame;
//      polled: nothing more, step() sends the command at the poll rate.
// step(): reads what arrived, decodes every verified frame of the configured command and
// hands out samples stamped through the device-clock filter. After silence_timeout_ms
// without a frame it returns `silence` and the next initialise() starts over; `closed` means
// the device went away and the caller must reopen the stream before initialise().
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "ugv/io/byte_stream.hpp"
#include "ugv/io/device_clock_filter.hpp"
#include "ugv/microstrain_gx1/sample_plausibility.hpp"
#include "ugv/microstrain_gx1/frame_parser.hpp"
#include "ugv/microstrain_gx1/orientation.hpp"
#include "ugv/microstrain_gx1/scaling.hpp"
#include "ugv/microstrain_gx1/tick_unwrapper.hpp"

namespace ugv::microstrain_gx1 {

struct SessionConfig
{
    uint8_t command = cmd::stab_euler_accel_rate;  // 0x31; or any data command, e.g. 0x0C
    bool continuous = true;                        // false: poll the command at poll_rate_hz
    double poll_rate_hz = 50.0;
    int baud = 38400;                              // for dating first bytes (10 bits per byte)
    int reply_timeout_ms = 300;                    // per handshake request
    int retries = 3;                               // per handshake request
    int stop_settle_ms = 100;                      // after `10 00 00`, before the flush
    int silence_timeout_ms = 1000;                 // no frame for this long: re-initialise
    int64_t latency_us = 0;                        // device sampling-to-first-byte latency
};

struct DeviceInfo
{
    uint16_t firmware_version = 0;
    uint16_t serial_number = 0;
    GainScales gains;
    TimingWords timing;
    double tick_period_s = 0;
};

struct Sample
{
    int64_t utime = 0;          // measurement time (us since the epoch), filtered
    int64_t arrival_utime = 0;  // host time of the frame's first byte (raw)
    int64_t device_ticks = 0;   // unwrapped timer
    DeviceSample device;        // as the device reported it (NED, sensor axes)
    Measurement body;           // body FLU / world ENU
};

struct SessionCounters
{
    uint64_t samples = 0;
    uint64_t initialisations = 0;      // successful handshakes
    uint64_t handshake_failures = 0;
    uint64_t request_timeouts = 0;     // handshake requests not answered in time
    uint64_t silences = 0;             // streams that went quiet
    uint64_t eeprom_invalid = 0;       // EEPROM gains/timing refused (defaults kept)
    uint64_t clock_restarts = 0;
    uint64_t implausible = 0;          // frames with a valid checksum that disagreed with both neighbours

    template <class F>
    void visit(F&& f) const
    {
        f("samples", samples);
        f("initialisations", initialisations);
        f("handshake_failures", handshake_failures);
        f("request_timeouts", request_timeouts);
        f("silences", silences);
        f("eeprom_invalid", eeprom_invalid);
        f("clock_restarts", clock_restarts);
        f("implausible", implausible);
    }
};

class Session
{
public:
    enum class Status {
        ok,       // initialise: streaming; step: healthy (maybe no sample this time)
        failed,   // initialise: the device did not answer (see error())
        silence,  // step: no frame within the silence timeout; call initialise()
        closed    // the stream is gone (hang-up, EIO): reopen it, then initialise()
    };
    using SampleHandler = std::function<void(const Sample&)>;

    Session(io::ByteStream& stream, SessionConfig config, FrameConverter converter = FrameConverter());

    Status initialise();
    // Checked while waiting in initialise(): true makes it give up at once (shutdown).
    void set_abort(std::function<bool()> should_abort) { should_abort_ = std::move(should_abort); }
    Status step(int wait_ms, const SampleHandler& on_sample);
    bool streaming() const { return streaming_; }

    const DeviceInfo& info() const { return info_; }
    const SessionCounters& counters() const { return counters_; }
    const ParserCounters& parser_counters() const { return parser_.counters(); }
    const std::string& error() const { return error_; }
    const SessionConfig& config() const { return config_; }

private:
    // Sends request and waits for a verified reply echoing `echo`; retries on timeout.
    Status transact(const std::vector<uint8_t>& request, uint8_t echo, Frame& reply);
    // Reads for up to wait_ms and feeds the parser. closed on hang-up / error.
    Status pump(int wait_ms);
    Status read_eeprom(uint16_t address, uint16_t& value);
    void emit(const Frame& f, const SampleHandler& on_sample);

    io::ByteStream& stream_;
    SessionConfig config_;
    FrameConverter converter_;
    FrameParser parser_;
    io::DeviceClockFilter clock_;
    TickUnwrapper ticks_;
    SamplePlausibility plausibility_;
    DeviceInfo info_;
    SessionCounters counters_;
    std::string error_;
    std::function<bool()> should_abort_;
    bool streaming_ = false;
    int64_t last_frame_us_ = 0;  // monotonic
    int64_t next_poll_us_ = 0;   // monotonic
};

}  // namespace ugv::microstrain_gx1
