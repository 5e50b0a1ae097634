// The receiver session, against any ugv::io::ByteStream.
//
// configure mode: UNLOGALL, optionally COM <baud> (then the host follows), then one
// LOG <message> ONTIME <period> per requested log, each answered "<OK" (an "<ERROR:..." or
// no reply within reply_timeout_ms fails the start). If UNLOGALL gets no reply at the open
// baud but a COM baud is configured, the receiver may still be at that baud from an earlier
// run: the session tries there once before failing. Still no reply and probe_bauds given: it
// tries UNLOGALL at each of those rates (a receiver left at another rate by someone else), and
// once one answers, switches the receiver back to the configured rate with COM (the port
// then runs at com_baud, else at the open rate). found_at_baud() tells where it was.
// passive mode: sends nothing; a receiver configured by someone else is just read.
//
// Silence: no valid frame for silence_timeout_us -> poll() reports `silent` (and again on
// every poll until a frame comes). The device is still there: the caller reports DEGRADED
// and keeps reading the same open port (configure mode may start() again on it, as a
// receiver that restarted has forgotten its logs). Only `closed` -- EIO, a hang-up, the node
// vanished or replaced (io::SerialPort) -- means the port must be reopened.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "ugv/io/byte_stream.hpp"
#include "ugv/novatel/decoder.hpp"

namespace ugv::novatel {

struct LogRequest
{
    std::string message;  // e.g. "BESTPOSB", "GPGGA"
    double period_s = 1.0;
};

struct SessionConfig
{
    bool configure = true;           // false: passive
    std::vector<LogRequest> logs;
    int com_baud = 0;                // > 0: switch the receiver's port (and the host) to it
    int reply_timeout_ms = 1000;
    int64_t silence_timeout_us = 2'000'000;
    std::vector<int> probe_bauds;    // configure mode: rates to look for a silent receiver at
};

struct SessionCounters
{
    uint64_t commands_sent = 0;
    uint64_t commands_failed = 0;    // <ERROR or no reply
    uint64_t starts = 0;
    uint64_t found_by_probing = 0;   // starts that found the receiver at a probed rate

    template <class F>
    void visit(F&& f) const
    {
        f("commands_sent", commands_sent);
        f("commands_failed", commands_failed);
        f("starts", starts);
        f("found_by_probing", found_by_probing);
    }
    // A daemon keeps the sum over the sessions it ran.
    SessionCounters& operator+=(const SessionCounters& o)
    {
        commands_sent += o.commands_sent;
        commands_failed += o.commands_failed;
        starts += o.starts;
        found_by_probing += o.found_by_probing;
        return *this;
    }
};

class Session
{
public:
    enum class Status { ok, silent, closed, error };

    Session(io::ByteStream& stream, Decoder& decoder, SessionConfig config);

    // Configures the receiver (configure mode) or does nothing (passive). Messages arriving
    // meanwhile go to sink. False with error() saying why.
    bool start(const Decoder::Sink& sink);
    // Reads once (waiting up to timeout_ms) and decodes. `closed` when the device went away,
    // `silent` when no valid frame arrived within the silence timeout.
    Status poll(int timeout_ms, const Decoder::Sink& sink);

    // Sees every chunk read (bytes, arrival time), e.g. to log the raw stream.
    using RawTap = std::function<void(const uint8_t* data, std::size_t n, int64_t utime)>;
    void set_raw_tap(RawTap tap) { raw_tap_ = std::move(tap); }

    const std::string& error() const { return error_; }
    // True once the stream reported the device gone (in start() or poll()): reopen it.
    bool stream_closed() const { return stream_closed_; }
    // The rate the receiver answered at in the last start (0 before one answered).
    int found_at_baud() const { return found_at_baud_; }
    const SessionCounters& counters() const { return counters_; }
    const SessionConfig& config() const { return config_; }

private:
    enum class Reply { ok, error, timeout, closed };
    Reply command(const std::string& text, const Decoder::Sink& sink);
    // Feeds one read into the decoder; tracks frame activity. False when the stream closed.
    bool read_once(int timeout_ms, const Decoder::Sink& sink, io::ReadResult& result);
    bool fail(const std::string& why);
    // UNLOGALL at the open rate (twice), then the COM rate, then each probe rate, until one
    // answers. tried: the rates other than the open one, for the error.
    Reply find_receiver(const Decoder::Sink& sink, std::string& tried);
    Reply unlogall_at(int baud, const Decoder::Sink& sink);

    io::ByteStream& stream_;
    Decoder& decoder_;
    SessionConfig config_;
    SessionCounters counters_;
    std::string error_;
    std::vector<uint8_t> buf_;
    uint64_t frames_seen_ = 0;
    int64_t last_frame_us_ = 0;      // monotonic
    // While a command waits: its reply, caught from the decoded stream.
    Reply pending_ = Reply::timeout;
    bool awaiting_ = false;
    std::string last_reply_;
    RawTap raw_tap_;
    int found_at_baud_ = 0;
    bool stream_closed_ = false;
};

}  // namespace ugv::novatel
