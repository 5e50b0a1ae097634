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
        stream_closed_ = true;
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
        stream_closed_ = true;
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

Session::Reply Session::unlogall_at(int baud, const Decoder::Sink& sink)
{
    if (baud != stream_.baud()) {
        if (!stream_.set_baud(baud)) {
            return Reply::timeout;  // the host cannot do this rate: nothing to hear there
        }
        decoder_.reset();
    }
    stream_.flush_input();
    return command(unlogall_command(), sink);
}

Session::Reply Session::find_receiver(const Decoder::Sink& sink, std::string& tried)
{
    const int open_baud = stream_.baud();
    // Twice at the open rate: on a noisy line one lost reply must not send us probing.
    std::vector<int> rates{open_baud, open_baud};
    // Perhaps still at the COM baud of an earlier run (the receiver kept its settings).
    if (config_.com_baud > 0 && config_.com_baud != open_baud) {
        rates.push_back(config_.com_baud);
    }
    for (const int b : config_.probe_bauds) {
        if (std::find(rates.begin(), rates.end(), b) == rates.end()) {
            rates.push_back(b);
        }
    }
    for (const int baud : rates) {
        const Reply r = unlogall_at(baud, sink);
        if (baud != open_baud) {
            tried += (tried.empty() ? "" : ", ") + std::to_string(baud);
        }
        if (r != Reply::timeout) {
            if (r == Reply::ok) {
                found_at_baud_ = baud;
            }
            return r;
        }
    }
    stream_.set_baud(open_baud);
    return Reply::timeout;
}

bool Session::start(const Decoder::Sink& sink)
{
    ++counters_.starts;
    error_.clear();
    found_at_baud_ = 0;
    decoder_.reset();
    last_frame_us_ = io::monotonic_us();  // the silence clock starts now
    if (!config_.configure) {
        return true;
    }
    const int open_baud = stream_.baud();
    std::string tried;
    Reply r = find_receiver(sink, tried);
    if (r == Reply::closed) {
        return fail("device closed during configuration: " + stream_.last_error());
    }
    if (r != Reply::ok) {
        if (r == Reply::error) {
            return fail("UNLOGALL: " + last_reply_);
        }
        return fail("UNLOGALL: no reply at the configured " + std::to_string(open_baud) + " baud" +
                    (tried.empty() ? "" : " (nor at " + tried + ")"));
    }
    const int wanted_baud = config_.com_baud > 0 ? config_.com_baud : open_baud;
    if (found_at_baud_ != open_baud && found_at_baud_ != config_.com_baud) {
        ++counters_.found_by_probing;
    }
    if (wanted_baud != stream_.baud()) {
        // The receiver answers at the old rate, then switches.
        r = command(com_command(wanted_baud), sink);
        if (r != Reply::ok) {
            return fail("COM " + std::to_string(wanted_baud) + ": " + (r == Reply::error ? last_reply_ : "no reply"));
        }
        stream_.drain_output();
        if (!stream_.set_baud(wanted_baud)) {
            return fail("host refused baud " + std::to_string(wanted_baud) + ": " + stream_.last_error());
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
        error_ = stream_.last_error().empty() ? "device closed" : stream_.last_error();
        return r.status == io::ReadResult::Status::closed ? Status::closed : Status::error;
    }
    if (io::monotonic_us() - last_frame_us_ > config_.silence_timeout_us) {
        // At the wrong rate the port delivers bytes but never a frame: say which rate it was.
        error_ = "no valid frame for " + std::to_string(config_.silence_timeout_us / 1000) + " ms at " +
                 std::to_string(stream_.baud()) + " baud";
        return Status::silent;
    }
    return Status::ok;
}

}  // namespace ugv::novatel
