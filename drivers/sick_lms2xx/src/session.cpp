#include "ugv/sick_lms2xx/session.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <thread>
#include <utility>

#include "ugv/sick_lms2xx/model.hpp"
#include "ugv/sick_lms2xx/requests.hpp"
#include "ugv/sick_lms2xx/timing.hpp"

namespace ugv::sick_lms2xx {

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr int kProbeAttempts = 2;
constexpr int kReadSliceMs = 50;  // longest single wait, so stop requests are seen quickly
}  // namespace

void validate(const SessionConfig& c)
{
    if (!baud_mode_byte(c.baud)) throw std::invalid_argument("baud: must be 9600, 19200, 38400 or 500000");
    if (c.angle_deg != 100 && c.angle_deg != 180) throw std::invalid_argument("angle_deg: must be 100 or 180");
    if (c.resolution_cdeg != 25 && c.resolution_cdeg != 50 && c.resolution_cdeg != 100)
        throw std::invalid_argument("resolution_deg: must be 0.25, 0.5 or 1.0");
    if (c.resolution_cdeg == 25 && c.angle_deg != 100)
        throw std::invalid_argument("resolution_deg: 0.25 deg needs angle_deg = 100");
    if (c.password.size() != 8) throw std::invalid_argument("password: must be 8 characters");
    if (c.reply_timeout_ms < 10 || c.attempts < 1 || c.silence_periods < 1)
        throw std::invalid_argument("timeouts: reply_timeout_ms >= 10, attempts >= 1, silence_periods >= 1");
    try {
        (void)parse_sweep_order(c.sweep_order, c.resolution_cdeg);
    } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(std::string("sweep_order: ") + e.what());
    }
}

const char* to_string(SessionState s)
{
    switch (s) {
    case SessionState::probing: return "probing";
    case SessionState::configuring: return "configuring";
    case SessionState::streaming: return "streaming";
    case SessionState::recovering: return "recovering";
    case SessionState::stopped: return "stopped";
    }
    return "?";
}

Session::Session(io::ByteStream& stream, SessionConfig config, SessionCallbacks callbacks)
    : stream_(stream), config_(std::move(config)), cb_(std::move(callbacks)), decoder_(kDeviceAddress)
{
    validate(config_);
    if (!cb_.monotonic_us)
        cb_.monotonic_us = [] {
            return std::chrono::duration_cast<std::chrono::microseconds>(
                       std::chrono::steady_clock::now().time_since_epoch())
                .count();
        };
    if (!cb_.sleep_us) cb_.sleep_us = [](int64_t us) { std::this_thread::sleep_for(std::chrono::microseconds(us)); };
    expected_beams_ = beams_per_scan(config_.angle_deg, config_.resolution_cdeg);
    sweep_order_ = parse_sweep_order(config_.sweep_order, config_.resolution_cdeg);
    rx_.resize(4096);
}

int64_t Session::now_us() const { return cb_.monotonic_us(); }
bool Session::stopping() const { return cb_.stop_requested && cb_.stop_requested(); }

void Session::sleep(int64_t us)
{
    // In slices, so a stop request is not kept waiting behind a long back-off.
    const int64_t end = now_us() + us;
    for (int64_t left = us; left > 0 && !stopping(); left = end - now_us())
        cb_.sleep_us(std::min<int64_t>(left, kReadSliceMs * 1000));
}

void Session::set_state(SessionState s, const std::string& why)
{
    state_ = s;
    if (cb_.on_state) cb_.on_state(s, why);
}

bool Session::fail(const std::string& why)
{
    error_ = why;
    return false;
}

double Session::silence_timeout_s() const
{
    // At a slow rate the line, not the mirror, limits the scan rate (0.5 deg at 38400: one
    // scan every ~0.2 s), so the expected interval is the longer of the two.
    const std::size_t scan_bytes = kHeaderBytes + 4 + 2 * static_cast<std::size_t>(expected_beams_) + 1 + kCrcBytes;
    const double interval = std::max(scan_period_s(config_.resolution_cdeg), line_time_s(scan_bytes, config_.baud) * 1.2);
    return std::max(config_.silence_periods * interval, 0.5);
}

void Session::sync_decoder_stats()
{
    const DecoderStats& d = decoder_.stats();
    stats_.crc_errors = static_cast<int64_t>(d.crc_errors);
    stats_.resyncs = static_cast<int64_t>(d.resyncs);
}

io::ReadResult::Status Session::read_some(int timeout_ms)
{
    const io::ReadResult r = stream_.read(rx_.data(), rx_.size(), std::max(0, timeout_ms));
    if (r.status == io::ReadResult::Status::data && r.n > 0) {
        stats_.bytes_in += static_cast<int64_t>(r.n);
        if (cb_.on_bytes) cb_.on_bytes(rx_.data(), r.n, r.utime, true);
        chunk_utime_ = r.utime;
        decoder_.feed(rx_.data(), r.n, [this](const DecoderEvent& ev) { on_event(ev); });
        sync_decoder_stats();
    } else if (r.status == io::ReadResult::Status::closed || r.status == io::ReadResult::Status::error) {
        closed_ = true;
        error_ = "device gone: " + stream_.last_error();
        return io::ReadResult::Status::closed;
    }
    return r.status;
}

void Session::on_event(const DecoderEvent& ev)
{
    switch (ev.kind) {
    case DecoderEvent::Kind::ack: got_ack_ = true; return;
    case DecoderEvent::Kind::nak:
        if (awaiting_cmd_ >= 0) got_nak_ = true;
        return;
    case DecoderEvent::Kind::bad_crc: return;
    case DecoderEvent::Kind::telegram: break;
    }
    const Telegram& t = ev.telegram;
    got_telegram_ = true;
    if (t.command == cmd::scan) {
        if (streaming_) handle_scan(t);
        return;
    }
    if (awaiting_cmd_ >= 0 && t.command == awaiting_cmd_) {
        reply_.assign(t.data.begin(), t.data.end());
        got_reply_ = true;
    }
}

uint64_t Session::rejected_telegrams() const
{
    const DecoderStats& ds = decoder_.stats();
    return ds.crc_errors + ds.length_errors + static_cast<uint64_t>(stats_.bad_scans.load());
}

void Session::handle_scan(const Telegram& t)
{
    if (decode_scan(t, scan_.scan) != ScanError::none ||
        scan_.scan.ranges_m.size() != static_cast<std::size_t>(expected_beams_)) {
        ++stats_.bad_scans;
        return;
    }
    const double period = scan_period_s(config_.resolution_cdeg);
    // The bytes read after this telegram in the same chunk came after its last byte.
    const int64_t last_byte_utime =
        chunk_utime_ - std::llround(line_time_s(decoder_.buffered(), device_baud_) * 1e6);
    const uint64_t rejected = rejected_telegrams();
    const int lost = static_cast<int>(std::min<uint64_t>(rejected - std::exchange(rejected_at_last_scan_, rejected), 1000));
    const int64_t arrival = scan_clock_.update(last_byte_utime, lost);
    stats_.clock_restarts = static_cast<int64_t>(scan_clock_.restarts());
    const ScanStamp stamp = stamp_scan(scan_end_utime(arrival, t.raw.size(), device_baud_), config_.angle_deg,
                                       config_.resolution_cdeg, config_.beam_timing, sweep_order_);
    scan_.arrival_utime = last_byte_utime;
    scan_.first_beam_utime = stamp.first_beam_utime;
    scan_.time_increment_s = stamp.time_increment_s;
    scan_.sweep_period_s = stamp.sweep_period_s;
    scan_.sweep_order = stamp.order;
    scan_.scan_period_s = period;
    scan_.angle_min_rad = -config_.angle_deg / 2.0 * kPi / 180.0;
    scan_.angle_increment_rad = config_.resolution_cdeg / 100.0 * kPi / 180.0;
    scan_.range_max_m = range_max_m(scan_.scan.units);
    last_scan_us_ = now_us();
    ++stats_.scans;
    if (cb_.on_scan) cb_.on_scan(scan_);
}

bool Session::write(const std::vector<uint8_t>& bytes)
{
    if (cb_.on_bytes) cb_.on_bytes(bytes.data(), bytes.size(), 0, false);
    if (!stream_.write(bytes.data(), bytes.size())) {
        closed_ = true;
        return fail("write failed: " + stream_.last_error());
    }
    return true;
}

bool Session::transact(const std::vector<uint8_t>& request, uint8_t reply_cmd, int attempts, const char* what)
{
    const int64_t timeout_us = int64_t{config_.reply_timeout_ms} * 1000;
    int naks = 0;
    for (int attempt = 0; attempt < attempts && !stopping(); ++attempt) {
        awaiting_cmd_ = reply_cmd;
        got_ack_ = got_nak_ = got_reply_ = false;
        if (!write(request)) break;
        int64_t deadline = now_us() + timeout_us;
        // A busy line (scans in flight) may delay the reply, but never beyond a few timeouts.
        const int64_t hard_deadline = now_us() + 4 * timeout_us;
        while (!got_reply_ && !got_nak_ && !stopping()) {
            const int64_t left = deadline - now_us();
            if (left <= 0) break;
            got_telegram_ = false;
            if (read_some(static_cast<int>(std::min<int64_t>(left / 1000 + 1, kReadSliceMs))) ==
                io::ReadResult::Status::closed) {
                awaiting_cmd_ = -1;
                return false;
            }
            if (got_telegram_) deadline = std::min(hard_deadline, std::max(deadline, now_us() + timeout_us));
        }
        if (got_reply_) {
            awaiting_cmd_ = -1;
            return true;
        }
        if (got_nak_) {
            ++stats_.naks;
            ++naks;
        } else if (!stopping()) {
            ++stats_.timeouts;
        }
    }
    awaiting_cmd_ = -1;
    if (closed_) return false;
    return fail(std::string(what) + (naks == attempts ? ": refused (NAK) " : ": no reply after ") +
                std::to_string(attempts) + " attempts at " + std::to_string(stream_.baud()) + " baud");
}

bool Session::mode_switch(const std::vector<uint8_t>& request, const char* what)
{
    if (!transact(request, reply_command(cmd::switch_mode), config_.attempts, what)) return false;
    const uint8_t code = reply_.empty() ? 0xff : reply_[0];
    if (code == kModeOk) return true;
    if (code == kModeBadPassword) return fail(std::string(what) + ": wrong password");
    return fail(std::string(what) + ": refused with code " + std::to_string(code));
}

void Session::settle(int ms)
{
    const int64_t end = now_us() + int64_t{ms} * 1000;
    for (int64_t left = end - now_us(); left > 0 && !stopping() && !closed_; left = end - now_us())
        read_some(static_cast<int>(std::min<int64_t>(left / 1000 + 1, kReadSliceMs)));
    decoder_.reset();
}

bool Session::probe(int baud)
{
    if (!stream_.set_baud(baud)) return fail("cannot set the host to " + std::to_string(baud) + " baud: " + stream_.last_error());
    stream_.flush_input();
    decoder_.reset();
    // `20 25` is harmless in every state and stops a device left streaming.
    if (!transact(request_stop_streaming(), reply_command(cmd::switch_mode), kProbeAttempts, "probe")) return false;
    device_baud_ = baud;
    return true;
}

bool Session::switch_baud(int baud)
{
    if (!mode_switch(request_baud(baud), "baud switch")) return false;
    // The device changes rate after its reply; follow it, let the line settle, check.
    stream_.drain_output();
    if (!stream_.set_baud(baud)) return fail("cannot set the host to " + std::to_string(baud) + " baud: " + stream_.last_error());
    device_baud_ = baud;
    settle(config_.settle_ms);
    return mode_switch(request_stop_streaming(), "stop streaming after the baud switch");
}

bool Session::configure()
{
    if (!transact(request_type(), reply_command(cmd::type), config_.attempts, "type")) return false;
    device_type_.clear();
    for (const uint8_t c : reply_)
        if (c >= 0x20 && c < 0x7f) device_type_.push_back(static_cast<char>(c));
    device_model_ = model_from_type(device_type_).value_or(0);
    if (device_model_ == 0)
        set_state(SessionState::configuring,
                  "type '" + device_type_ + "' is not an LMS 200/211/220/221/291: configured as one");
    if (!transact(request_status(), reply_command(cmd::status), config_.attempts, "status")) return false;
    software_version_.clear();
    for (std::size_t i = 0; i < std::min<std::size_t>(7, reply_.size()); ++i)
        if (reply_[i] > 0x20 && reply_[i] < 0x7f) software_version_.push_back(static_cast<char>(reply_[i]));
    if (!transact(request_read_config(), reply_command(cmd::read_config), config_.attempts, "read configuration"))
        return false;
    if (reply_.size() < kConfigMinBytes) return fail("read configuration: block of " + std::to_string(reply_.size()) + " bytes");
    DeviceConfig dc{reply_};
    config_block_bytes_ = reply_.size();
    if (!mode_switch(request_installation_mode(config_.password), "installation mode")) return false;

    if (!transact(request_variant(config_.angle_deg, config_.resolution_cdeg), reply_command(cmd::variant),
                  config_.attempts, "variant"))
        return false;
    if (reply_.empty() || reply_[0] != 0x01)
        return fail("variant " + std::to_string(config_.angle_deg) + " deg / " +
                    std::to_string(config_.resolution_cdeg / 100.0) + " deg refused");

    const uint8_t avail = config_.scan_index ? static_cast<uint8_t>(dc.availability() | kAvailabilityScanIndex)
                                             : static_cast<uint8_t>(dc.availability() & ~kAvailabilityScanIndex);
    const uint8_t units = config_.units == Units::mm ? kConfigUnitsMm : kConfigUnitsCm;
    if (dc.availability() != avail || dc.measuring_mode() != kMeasuringMode8m80m || dc.units() != units) {
        dc.set_availability(avail);
        dc.set_measuring_mode(kMeasuringMode8m80m);
        dc.set_units(units);
        if (!transact(request_write_config(dc.block), reply_command(cmd::write_config), config_.attempts,
                      "write configuration"))
            return false;
        if (reply_.empty() || reply_[0] != 0x01) return fail("write configuration: refused");
    }
    return true;
}

bool Session::initialise()
{
    streaming_ = false;
    set_state(state_ == SessionState::stopped ? SessionState::probing : SessionState::recovering, error_);
    bool found = false;
    for (const int baud : kSupportedBauds) {
        if (stopping() || closed_) return false;
        if (probe(baud)) {
            found = true;
            break;
        }
    }
    if (!found) return closed_ ? false : fail("no LMS answered at 9600, 19200, 38400 or 500000 baud");
    set_state(SessionState::configuring, "found at " + std::to_string(device_baud_) + " baud");
    if (device_baud_ != config_.baud && !switch_baud(config_.baud)) return false;
    if (!configure()) return false;
    if (!mode_switch(request_start_streaming(), "start streaming")) return false;
    // A new stream: the count and the fit start again (the restarts so far stay counted).
    // A line too slow for every scan carries every n-th (the next one due once it is free).
    const double period_s = scan_period_s(config_.resolution_cdeg);
    const double telegram_s = line_time_s(2 * static_cast<std::size_t>(expected_beams_) + 10, device_baud_);
    const int scans_per_telegram = std::max(1, static_cast<int>(std::ceil(telegram_s / period_s - 1e-9)));
    scan_clock_ = io::PeriodicClock(period_s, scans_per_telegram, scan_clock_.restarts());
    rejected_at_last_scan_ = rejected_telegrams();
    streaming_ = true;
    last_scan_us_ = now_us();
    error_.clear();
    set_state(SessionState::streaming, device_type_ + (software_version_.empty() ? "" : " " + software_version_) +
                                           " at " + std::to_string(device_baud_) + " baud");
    return true;
}

Session::PumpResult Session::pump(int timeout_ms)
{
    if (stopping()) return PumpResult::stopped;
    if (read_some(std::min(timeout_ms, kReadSliceMs)) == io::ReadResult::Status::closed) return PumpResult::closed;
    if (static_cast<double>(now_us() - last_scan_us_) > silence_timeout_s() * 1e6) {
        ++stats_.timeouts;
        ++stats_.silences;
        error_ = "no scan for " + std::to_string(silence_timeout_s()) + " s";
        return PumpResult::silence;
    }
    return PumpResult::ok;
}

void Session::run()
{
    int64_t backoff_us = config_.backoff_initial_us;
    const auto back_off = [&] {
        sleep(backoff_us);
        backoff_us = std::min(backoff_us * 2, config_.backoff_max_us);
    };
    bool was_streaming = false;
    while (!stopping()) {
        if (closed_) {
            streaming_ = false;
            set_state(SessionState::recovering, error_.empty() ? "device closed" : error_);
            if (!cb_.reopen || !cb_.reopen()) {
                back_off();
                continue;
            }
            closed_ = false;
            ++stats_.reopens;
            decoder_.reset();
        }
        if (!initialise()) {
            if (!stopping()) {
                set_state(SessionState::recovering, error_);
                if (!closed_) back_off();
            }
            continue;
        }
        backoff_us = config_.backoff_initial_us;
        was_streaming = true;
        PumpResult r = PumpResult::ok;
        while (r == PumpResult::ok) r = pump(kReadSliceMs);
        if (r == PumpResult::stopped) break;
        streaming_ = false;
        if (was_streaming) ++stats_.reconnects;
        set_state(SessionState::recovering, error_);
    }
    shutdown();
    set_state(SessionState::stopped);
}

void Session::shutdown()
{
    if (!streaming_ || closed_) return;
    streaming_ = false;
    if (!config_.stop_on_exit) return;
    // One attempt: a clean exit must not wait on a device that no longer answers.
    const auto stop = cb_.stop_requested;
    cb_.stop_requested = nullptr;
    transact(request_stop_streaming(), reply_command(cmd::switch_mode), 1, "stop streaming on exit");
    cb_.stop_requested = stop;
}

}  // namespace ugv::sick_lms2xx
