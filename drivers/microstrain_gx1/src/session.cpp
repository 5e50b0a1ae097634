#include "ugv/microstrain_gx1/session.hpp"

#include <algorithm>
#include <array>
#include <cstdio>

#include "ugv/io/clock.hpp"

namespace ugv::microstrain_gx1 {

namespace {
std::string hex(uint8_t b)
{
    char s[8];
    std::snprintf(s, sizeof s, "0x%02X", b);
    return s;
}
}  // namespace

Session::Session(io::ByteStream& stream, SessionConfig config, FrameConverter converter)
    : stream_(stream), config_(config), converter_(converter), parser_(10e6 / std::max(config.baud, 1))
{
}

Session::Status Session::pump(int wait_ms)
{
    std::array<uint8_t, 512> buf;
    const io::ReadResult r = stream_.read(buf.data(), buf.size(), std::max(wait_ms, 0));
    switch (r.status) {
    case io::ReadResult::Status::data: parser_.feed(buf.data(), r.n, r.utime); return Status::ok;
    case io::ReadResult::Status::timeout: return Status::ok;
    case io::ReadResult::Status::closed:
    case io::ReadResult::Status::error:
        error_ = "device lost: " + stream_.last_error();
        streaming_ = false;
        return Status::closed;
    }
    return Status::ok;
}

Session::Status Session::transact(const std::vector<uint8_t>& request, uint8_t echo, Frame& reply)
{
    parser_.accept_only({echo});
    for (int attempt = 0; attempt <= config_.retries; ++attempt) {
        if (!stream_.write(request.data(), request.size())) {
            error_ = "write failed: " + stream_.last_error();
            return Status::closed;
        }
        const int64_t deadline = io::monotonic_us() + int64_t{config_.reply_timeout_ms} * 1000;
        for (int64_t now = io::monotonic_us(); now < deadline; now = io::monotonic_us()) {
            if (should_abort_ && should_abort_()) {
                error_ = "handshake aborted";
                return Status::failed;
            }
            if (pump(static_cast<int>(std::min<int64_t>((deadline - now + 999) / 1000, 100))) == Status::closed)
                return Status::closed;
            if (parser_.next(reply)) return Status::ok;
        }
        ++counters_.request_timeouts;
    }
    error_ = "no reply to command " + hex(echo) + " after " + std::to_string(config_.retries + 1) + " attempts";
    return Status::failed;
}

Session::Status Session::read_eeprom(uint16_t address, uint16_t& value)
{
    Frame f;
    const Status st = transact(encode_read_eeprom(address), cmd::read_eeprom, f);
    if (st == Status::ok) value = f.words[0];
    return st;
}

Session::Status Session::initialise()
{
    streaming_ = false;
    auto fail = [this](Status st) {
        ++counters_.handshake_failures;
        return st;
    };

    // 1. Stop a stream the unit may have been left in, let the tail arrive, discard it.
    const auto stop = encode_stop_continuous();
    if (!stream_.write(stop.data(), stop.size())) {
        error_ = "write failed: " + stream_.last_error();
        return fail(Status::closed);
    }
    const int64_t settle_end = io::monotonic_us() + int64_t{config_.stop_settle_ms} * 1000;
    for (int64_t now = io::monotonic_us(); now < settle_end; now = io::monotonic_us())
        if (pump(static_cast<int>((settle_end - now + 999) / 1000)) == Status::closed) return fail(Status::closed);
    stream_.flush_input();
    parser_.clear();

    // 2. Identity.
    Frame f;
    if (Status st = transact(encode_simple(cmd::firmware_version), cmd::firmware_version, f); st != Status::ok)
        return fail(st);
    info_.firmware_version = f.words[0];
    if (Status st = transact(encode_simple(cmd::serial_number), cmd::serial_number, f); st != Status::ok)
        return fail(st);
    info_.serial_number = f.words[0];

    // 3. Per-unit gains and timer tick from EEPROM. A zero word would make the scaling
    //    meaningless: keep the typical value and count it.
    uint16_t gyro = 0, accel = 0, mag = 0;
    for (auto [address, out] : {std::pair{eeprom::gyro_gain_scale, &gyro}, std::pair{eeprom::accel_gain_scale, &accel},
                                std::pair{eeprom::mag_gain_scale, &mag}})
        if (Status st = read_eeprom(address, *out); st != Status::ok) return fail(st);
    TimingWords timing;
    for (std::size_t i = 0; i < timing.words.size(); ++i)
        if (Status st = read_eeprom(eeprom::timing[i], timing.words[i]); st != Status::ok) return fail(st);
    const GainScales typical;
    info_.gains.gyro = gyro > 0 ? gyro : typical.gyro;
    info_.gains.accel = accel > 0 ? accel : typical.accel;
    info_.gains.mag = mag > 0 ? mag : typical.mag;
    if (gyro == 0 || accel == 0 || mag == 0) ++counters_.eeprom_invalid;
    if (timing.tick_period_s() > 0) {
        info_.timing = timing;
    } else {
        info_.timing = TimingWords{};
        ++counters_.eeprom_invalid;
    }
    info_.tick_period_s = info_.timing.tick_period_s();

    // 4. Start the stream (or get ready to poll).
    if (config_.continuous) {
        parser_.accept_only({cmd::continuous, config_.command});
        const auto start = encode_start_continuous(config_.command);
        bool started = false;
        for (int attempt = 0; attempt <= config_.retries && !started; ++attempt) {
            if (!stream_.write(start.data(), start.size())) {
                error_ = "write failed: " + stream_.last_error();
                return fail(Status::closed);
            }
            const int64_t deadline = io::monotonic_us() + int64_t{config_.reply_timeout_ms} * 1000;
            for (int64_t now = io::monotonic_us(); now < deadline && !started; now = io::monotonic_us()) {
                if (pump(static_cast<int>((deadline - now + 999) / 1000)) == Status::closed) return fail(Status::closed);
                // The echo confirms; a data frame does too (the echo may have been damaged).
                while (!started && parser_.next(f))
                    started = f.command == config_.command ||
                              (f.command == cmd::continuous && (f.words[0] & 0xFF) == config_.command);
            }
            if (!started) ++counters_.request_timeouts;
        }
        if (!started) {
            error_ = "continuous mode " + hex(config_.command) + " did not start";
            return fail(Status::failed);
        }
    }
    parser_.accept_only({config_.command});
    clock_.reset();
    ticks_.reset();
    plausibility_.reset();
    streaming_ = true;
    last_frame_us_ = next_poll_us_ = io::monotonic_us();
    ++counters_.initialisations;
    error_.clear();
    return Status::ok;
}

void Session::emit(const Frame& f, const SampleHandler& on_sample)
{
    Sample s;
    s.device = decode_sample(f, info_.gains);
    // Before the timer reaches the unwrapper and the clock: a damaged timer word would move both.
    const bool plausible = plausibility_.check(s.device, info_.tick_period_s);
    counters_.implausible = plausibility_.implausible();
    if (!plausible) return;
    s.device_ticks = ticks_.unwrap(f.ticks());
    s.arrival_utime = f.first_byte_utime;
    const std::size_t restarts = clock_.restarts();
    s.utime = clock_.update(static_cast<double>(s.device_ticks) * info_.tick_period_s, f.first_byte_utime) -
              config_.latency_us;
    counters_.clock_restarts += clock_.restarts() - restarts;
    s.body = converter_.convert(s.device);
    ++counters_.samples;
    on_sample(s);
}

Session::Status Session::step(int wait_ms, const SampleHandler& on_sample)
{
    if (!streaming_) return Status::silence;
    int64_t now = io::monotonic_us();
    if (!config_.continuous) {
        if (now >= next_poll_us_) {
            const uint8_t c = config_.command;
            if (!stream_.write(&c, 1)) {
                error_ = "write failed: " + stream_.last_error();
                streaming_ = false;
                return Status::closed;
            }
            const auto period_us = static_cast<int64_t>(1e6 / config_.poll_rate_hz);
            next_poll_us_ = std::max(next_poll_us_ + period_us, now);
        }
        wait_ms = static_cast<int>(std::clamp<int64_t>((next_poll_us_ - now + 999) / 1000, 0, wait_ms));
    }
    if (pump(wait_ms) == Status::closed) return Status::closed;
    Frame f;
    while (parser_.next(f)) {
        last_frame_us_ = io::monotonic_us();
        emit(f, on_sample);
    }
    now = io::monotonic_us();
    if (now - last_frame_us_ > int64_t{config_.silence_timeout_ms} * 1000) {
        streaming_ = false;
        ++counters_.silences;
        error_ = "no data for " + std::to_string(config_.silence_timeout_ms) + " ms";
        return Status::silence;
    }
    return Status::ok;
}

}  // namespace ugv::microstrain_gx1
