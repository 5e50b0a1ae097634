#include "ugv/novatel/session.hpp"

#include <algorithm>

#include "ugv/io/clock.hpp"
#include "ugv/novatel/encoding.hpp"

namespace ugv::novatel {
namespace {

constexpr std::size_t kReadChunk = 4096;

bool starts_with(const std::string& s, const char* prefix) { return s.rfind(prefix, 0) == 0; }

}  // namespace

Session::Session(io::ByteStream& stream, Decoder& decoder, SessionConfig config)
    : stream_(stream), decoder_(decoder), config_(std::move(config)), buf_(kReadChunk)
{
}

bool Session::fail(const std::string& why)
{
    error_ = why;
    return false;
}

bool Session::read_once(int timeout_ms, const Decoder::Sink& sink, io::ReadResult& r)
{
    r = stream_.read(buf_.data(), buf_.size(), timeout_ms);
    if (r.status == io::ReadResult::Status::closed || r.status == io::ReadResult::Status::error) {
        return false;
    }
    if (r.status == io::ReadResult::Status::data) {
        if (raw_tap_) {
            raw_tap_(buf_.data(), r.n, r.utime);
        }
        decoder_.set_baud(stream_.baud());
        decoder_.feed(buf_.data(), r.n, r.utime, [&](const Decoded& d) {
            if (awaiting_) {
                if (const auto* reply = std::get_if<novatel::Reply>(&d.message);
                    reply && reply->kind == FrameKind::reply) {
                    if (reply->text == "OK") {
                        pending_ = Reply::ok;
                        awaiting_ = false;
                        return;
                    }
                    if (starts_with(reply->text, "ERROR")) {
                        pending_ = Reply::error;
                        last_reply_ = reply->text;
                        awaiting_ = false;
                        return;
                    }
                }
            }
            sink(d);
        });
        const uint64_t frames = decoder_.splitter_counters().frames_total();
        if (frames != frames_seen_) {
            frames_seen_ = frames;
            last_frame_us_ = io::monotonic_us();
        }
    }
    return true;
}

Session::Reply Session::command(const std::string& text, const Decoder::Sink& sink)
{
    ++counters_.commands_sent;
    pending_ = Reply::timeout;
    awaiting_ = true;
    last_reply_.clear();
    if (!stream_.write(reinterpret_cast<const uint8_t*>(text.data()), text.size())) {
        awaiting_ = false;
        ++counters_.commands_failed;
        return Reply::closed;
    }
    const int64_t deadline = io::monotonic_us() + int64_t{config_.reply_timeout_ms} * 1000;
    io::ReadResult r;
    while (awaiting_) {
        const int64_t left_us = deadline - io::monotonic_us();
        if (left_us <= 0) {
            break;
        }
        if (!read_once(static_cast<int>(std::max<int64_t>(1, left_us / 1000)), sink, r)) {
            awaiting_ = false;
            ++counters_.commands_failed;
            return Reply::closed;
        }
    }
    awaiting_ = false;
    if (pending_ != Reply::ok) {
        ++counters_.commands_failed;
    }
    return pending_;
}

bool Session::start(const Decoder::Sink& sink)
{
    ++counters_.starts;
    error_.clear();
    decoder_.reset();
    last_frame_us_ = io::monotonic_us();  // the silence clock starts now
    if (!config_.configure) {
        return true;
    }
    const std::string unlogall = unlogall_command();
    stream_.flush_input();
    Reply r = command(unlogall, sink);
    const int open_baud = stream_.baud();
    const bool switch_baud = config_.com_baud > 0 && config_.com_baud != open_baud;
    if (r == Reply::timeout && switch_baud) {
        // Perhaps still at the COM baud of an earlier run (the receiver kept its settings).
        if (stream_.set_baud(config_.com_baud)) {
            stream_.flush_input();
            decoder_.reset();
            r = command(unlogall, sink);
            if (r != Reply::ok) {
                stream_.set_baud(open_baud);
            }
        }
    }
    if (r == Reply::closed) {
        return fail("device closed during configuration");
    }
    if (r != Reply::ok) {
        return fail("UNLOGALL: " + std::string(r == Reply::error ? last_reply_ : "no reply"));
    }
    if (config_.com_baud > 0 && config_.com_baud != stream_.baud()) {
        // The receiver answers at the old rate, then switches.
        r = command(com_command(config_.com_baud), sink);
        if (r != Reply::ok) {
            return fail("COM " + std::to_string(config_.com_baud) + ": " +
                        (r == Reply::error ? last_reply_ : "no reply"));
        }
        stream_.drain_output();
        if (!stream_.set_baud(config_.com_baud)) {
            return fail("host refused baud " + std::to_string(config_.com_baud) + ": " + stream_.last_error());
        }
        decoder_.reset();
    }
    for (const auto& log : config_.logs) {
        const std::string cmd = log_command(log.message, log.period_s);
        r = command(cmd, sink);
        if (r != Reply::ok) {
            return fail(cmd.substr(0, cmd.size() - 2) + ": " + (r == Reply::error ? last_reply_ : "no reply"));
        }
    }
    last_frame_us_ = io::monotonic_us();
    return true;
}

Session::Status Session::poll(int timeout_ms, const Decoder::Sink& sink)
{
    io::ReadResult r;
    if (!read_once(timeout_ms, sink, r)) {
        error_ = r.status == io::ReadResult::Status::closed ? "device closed" : stream_.last_error();
        return r.status == io::ReadResult::Status::closed ? Status::closed : Status::error;
    }
    if (io::monotonic_us() - last_frame_us_ > config_.silence_timeout_us) {
        error_ = "no valid frame for " + std::to_string(config_.silence_timeout_us / 1000) + " ms";
        return Status::silent;
    }
    return Status::ok;
}

}  // namespace ugv::novatel
