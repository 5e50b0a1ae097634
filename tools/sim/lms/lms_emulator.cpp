#include "lms_emulator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ugv/sick_lms2xx/replies.hpp"
#include "ugv/sick_lms2xx/requests.hpp"
#include "ugv/sick_lms2xx/timing.hpp"
#include "ugv/sim/line_faults.hpp"

namespace ugv::sim::lms {

namespace lms = ugv::sick_lms2xx;
using Bytes = std::vector<uint8_t>;

namespace {
constexpr double kPi = 3.14159265358979323846;
constexpr uint8_t kReplyStatus = 0x10;  // the STATUS byte of every reply (bit meanings unverified)
}  // namespace

Scene flat_floor_scene(double height_m, double pitch_rad)
{
    return [height_m, pitch_rad](double angle_rad) {
        // Beam direction (cos a, sin a, 0) in the sensor frame, pitched down: its downward
        // component is cos(a) sin(pitch).
        const double down = std::cos(angle_rad) * std::sin(pitch_rad);
        if (down <= 1e-9) return std::numeric_limits<double>::infinity();
        return height_m / down;
    };
}

LmsDevice::LmsDevice(DeviceOptions options)
    : options_(std::move(options)),
      rng_(options_.seed),
      baud_(options_.initial_baud),
      streaming_(options_.initially_streaming),
      config_(std::max(options_.variant.config_bytes, lms::kConfigMinBytes), 0)
{
    if (!options_.scene) options_.scene = flat_floor_scene(1.0, 10.0 * kPi / 180.0);
    config_[lms::DeviceConfig::units_at] = options_.variant.factory_units;
    config_[lms::DeviceConfig::measuring_mode_at] = options_.variant.factory_measuring_mode;
}

lms::Units LmsDevice::units() const
{
    return config_[lms::DeviceConfig::units_at] == lms::kConfigUnitsMm ? lms::Units::mm : lms::Units::cm;
}

bool LmsDevice::silent(int64_t now_us) const
{
    const Faults& f = options_.faults;
    if (f.silence_every_s <= 0.0 || f.silence_for_s <= 0.0 || epoch_us_ < 0) return false;
    const double t = static_cast<double>(now_us - epoch_us_) * 1e-6;
    return std::fmod(t, f.silence_every_s) >= f.silence_every_s - f.silence_for_s;
}

void LmsDevice::send(Bytes bytes, int host_baud, int64_t now_us, Bytes& out, bool is_telegram)
{
    if (bytes.empty() || silent(now_us)) return;
    line_free_us_ = std::max(line_free_us_, now_us) +
                    static_cast<int64_t>(lms::line_time_s(bytes.size(), baud_) * 1e6);
    if (host_baud != baud_) {
        // A receiver at another rate samples the wrong bit cells: it sees about
        // n * host/device bytes of nonsense and never a valid telegram.
        const double ratio = baud_ > 0 ? static_cast<double>(host_baud) / baud_ : 1.0;
        const auto n = static_cast<std::size_t>(std::clamp(static_cast<double>(bytes.size()) * ratio, 1.0,
                                                           4.0 * static_cast<double>(bytes.size())));
        std::uniform_int_distribution<int> byte(0, 255);
        for (std::size_t i = 0; i < n; ++i) out.push_back(static_cast<uint8_t>(byte(rng_)));
        return;
    }
    std::uniform_real_distribution<double> u(0.0, 1.0);
    if (is_telegram && options_.faults.garbage_probability > 0.0 && u(rng_) < options_.faults.garbage_probability) {
        std::uniform_int_distribution<int> len(1, 40), byte(0, 255);
        for (int i = len(rng_); i > 0; --i) out.push_back(static_cast<uint8_t>(byte(rng_)));
    }
    const std::size_t first = out.size();
    out.insert(out.end(), bytes.begin(), bytes.end());
    stats_.bytes_damaged +=
        sim::flip_bits(out.begin() + static_cast<std::ptrdiff_t>(first), out.end(), options_.faults.bit_error_rate, rng_);
}

void LmsDevice::reply(uint8_t command, const Bytes& data, int64_t now_us, int host_baud, Bytes& out)
{
    Bytes b{lms::kAck};
    const Bytes t = lms::encode_reply(command, data, kReplyStatus);
    b.insert(b.end(), t.begin(), t.end());
    send(std::move(b), host_baud, now_us, out, true);
}

void LmsDevice::nak(int host_baud, int64_t now_us, Bytes& out)
{
    ++stats_.naks;
    send(Bytes{lms::kNak}, host_baud, now_us, out, false);
}

void LmsDevice::receive(const uint8_t* data, std::size_t n, int host_baud, int64_t now_us, Bytes& out)
{
    if (epoch_us_ < 0) epoch_us_ = now_us;
    if (host_baud != baud_) {
        // Framing errors at the device: nothing it can parse, and any partial frame is lost.
        stats_.garbled_input += n;
        decoder_.reset();
        return;
    }
    pending_baud_ = 0;
    decoder_.feed(data, n, [&](const lms::DecoderEvent& ev) {
        // After a baud switch (or a reset) the rest of this chunk was sent at the old rate: noise.
        if (pending_baud_ != 0) return;
        if (ev.kind == lms::DecoderEvent::Kind::bad_crc) {
            nak(host_baud, now_us, out);
            return;
        }
        if (ev.kind != lms::DecoderEvent::Kind::telegram) return;
        ++stats_.requests;
        const lms::Telegram& t = ev.telegram;
        if (t.command == lms::cmd::switch_mode && t.data.size() == 1) {
            if (const int b = [&] {
                    for (const int rate : lms::kSupportedBauds)
                        if (lms::baud_mode_byte(rate) == t.data[0]) return rate;
                    return 0;
                }();
                b != 0) {
                reply(lms::reply_command(lms::cmd::switch_mode), Bytes{lms::kModeOk}, now_us, host_baud, out);
                pending_baud_ = b;
                return;
            }
        }
        handle(t, now_us, host_baud, out);
    });
    // Applied after the decoder returns: it must not be reset from inside its own callback.
    if (pending_baud_ != 0) {
        if (pending_baud_ != baud_) ++stats_.baud_switches;
        baud_ = pending_baud_;
        pending_baud_ = 0;
        decoder_.reset();
    }
}

void LmsDevice::handle_mode(const lms::Telegram& t, int64_t now_us, int host_baud, Bytes& out)
{
    const uint8_t mode = t.data[0];
    const uint8_t a0 = lms::reply_command(lms::cmd::switch_mode);
    switch (mode) {
    case lms::kModeInstallation: {
        const std::string given(t.data.begin() + 1, t.data.end());
        const bool ok = given == options_.password;
        installation_ = ok;
        reply(a0, Bytes{ok ? lms::kModeOk : lms::kModeBadPassword}, now_us, host_baud, out);
        return;
    }
    case lms::kModeStreamAll:
        installation_ = false;
        if (!streaming_) next_scan_us_ = now_us + static_cast<int64_t>(lms::scan_period_s(resolution_cdeg_) * 1e6);
        streaming_ = true;
        reply(a0, Bytes{lms::kModeOk}, now_us, host_baud, out);
        return;
    case lms::kModeRequest:
        installation_ = false;
        streaming_ = false;
        reply(a0, Bytes{lms::kModeOk}, now_us, host_baud, out);
        return;
    default: nak(host_baud, now_us, out); return;
    }
}

void LmsDevice::handle(const lms::Telegram& t, int64_t now_us, int host_baud, Bytes& out)
{
    const auto& d = t.data;
    switch (t.command) {
    case lms::cmd::switch_mode:
        if (d.empty()) break;
        handle_mode(t, now_us, host_baud, out);
        return;
    case lms::cmd::type:
        reply(lms::reply_command(t.command),
              Bytes(options_.variant.type_string.begin(), options_.variant.type_string.end()), now_us, host_baud, out);
        return;
    case lms::cmd::status: {
        reply(lms::reply_command(t.command), status_block(options_.variant, streaming_), now_us, host_baud, out);
        return;
    }
    case lms::cmd::variant: {
        if (d.size() != 4) break;
        const int angle = lms::get_u16le(d.data());
        const int res = lms::get_u16le(d.data() + 2);
        const bool valid = (angle == 180 && (res == 50 || res == 100)) || (angle == 100 && (res == 25 || res == 50 || res == 100));
        const bool accept = valid && !streaming_;
        if (accept) {
            angle_deg_ = angle;
            resolution_cdeg_ = res;
            beam_ranges_.clear();
        }
        Bytes r{static_cast<uint8_t>(accept ? 0x01 : 0x00)};
        lms::put_u16le(r, static_cast<uint16_t>(angle_deg_));
        lms::put_u16le(r, static_cast<uint16_t>(resolution_cdeg_));
        reply(lms::reply_command(t.command), r, now_us, host_baud, out);
        return;
    }
    case lms::cmd::read_config:
        reply(lms::reply_command(t.command), config_, now_us, host_baud, out);
        return;
    case lms::cmd::write_config: {
        if (d.size() < lms::kConfigMinBytes) break;
        const auto& modes = options_.variant.measuring_modes;
        const bool mode_ok = std::find(modes.begin(), modes.end(), d[lms::DeviceConfig::measuring_mode_at]) != modes.end();
        const bool accept = installation_ && d.size() == config_.size() && mode_ok;
        if (accept) config_.assign(d.begin(), d.end());
        Bytes r{static_cast<uint8_t>(accept ? 0x01 : 0x00)};
        r.insert(r.end(), config_.begin(), config_.end());
        reply(lms::reply_command(t.command), r, now_us, host_baud, out);
        return;
    }
    case lms::cmd::reset:
        reply(lms::cmd::reset_reply, Bytes{}, now_us, host_baud, out);
        pending_baud_ = 9600;  // a reset device powers up at 9600
        streaming_ = false;
        installation_ = false;
        return;
    default: break;
    }
    nak(host_baud, now_us, out);
}

bool set_sweep_order(DeviceOptions& options, const std::string& digits)
{
    const std::size_t n = digits.size();
    if (n != 2 && n != 4) return false;
    std::vector<int> order;
    for (const char c : digits) {
        const int d = c - '0';
        if (d < 0 || d >= static_cast<int>(n) || std::find(order.begin(), order.end(), d) != order.end()) return false;
        order.push_back(d);
    }
    (n == 2 ? options.sweep_order_05 : options.sweep_order_025) = order;
    return true;
}

Bytes LmsDevice::make_scan(int64_t now_us)
{
    const int n = lms::beams_per_scan(angle_deg_, resolution_cdeg_);
    if (options_.beam_scene) {
        beam_ranges_.resize(static_cast<std::size_t>(n));
        const bool indexed = (config_[lms::DeviceConfig::availability_at] & lms::kAvailabilityScanIndex) != 0;
        const std::size_t telegram_bytes = lms::encode_scan_telegram(std::vector<uint16_t>(beam_ranges_.size(), 0),
                                                                     units(), 0, indexed ? 0 : -1, kReplyStatus)
                                               .size();
        // A pty has no line rate: the whole telegram reaches the host when it is sent
        // (now_us, the scan's due time), which the host reads as its last byte arriving
        // then, so the last beam was measured one transmission time (at the device's rate) before.
        const double tx_us = static_cast<double>(telegram_bytes) * 10.0 * 1e6 / baud_;
        const double last_beam_us = static_cast<double>(now_us) - tx_us;
        for (int i = 0; i < n; ++i) {
            const double deg = -angle_deg_ / 2.0 + i * resolution_cdeg_ / 100.0;
            const auto t = static_cast<int64_t>(std::llround(beam_time_us(i, n, last_beam_us)));
            beam_ranges_[static_cast<std::size_t>(i)] = options_.beam_scene(deg * kPi / 180.0, t);
        }
    } else if (beam_ranges_.size() != static_cast<std::size_t>(n)) {
        beam_ranges_.resize(static_cast<std::size_t>(n));
        for (int i = 0; i < n; ++i) {
            const double deg = -angle_deg_ / 2.0 + i * resolution_cdeg_ / 100.0;
            beam_ranges_[static_cast<std::size_t>(i)] = options_.scene(deg * kPi / 180.0);
        }
    }
    const lms::Units u = units();
    std::vector<uint16_t> values(beam_ranges_.size());
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = lms::encode_range(beam_ranges_[i], u);
    const bool with_index = (config_[lms::DeviceConfig::availability_at] & lms::kAvailabilityScanIndex) != 0;
    const int index = with_index ? static_cast<int>(scan_counter_ & 0xff) : -1;
    ++scan_counter_;
    return lms::encode_scan_telegram(values, u, 0, index, kReplyStatus);
}

double LmsDevice::beam_time_us(int i, int n, double last_beam_us) const
{
    const int sweeps = resolution_cdeg_ <= 25 ? 4 : resolution_cdeg_ <= 50 ? 2 : 1;
    const double turn_us = 1e6 / 75.0;
    if (options_.linear_timing) {
        const double duration_us = sweeps * turn_us;
        return last_beam_us - duration_us + duration_us * i / std::max(1, n - 1);
    }
    const std::vector<int>& order = sweeps == 4 ? options_.sweep_order_025 : options_.sweep_order_05;
    int sweep = 0;
    for (int k = 0; k < sweeps; ++k)
        if (order[static_cast<std::size_t>(k)] == i % sweeps) sweep = k;
    // The last sweep ends at the far edge of the field: its start is a field's crossing earlier.
    const double last_sweep_start_us = last_beam_us - angle_deg_ * turn_us / 360.0;
    const double angle_deg = i * resolution_cdeg_ / 100.0;
    return last_sweep_start_us - (sweeps - 1 - sweep) * turn_us + angle_deg * turn_us / 360.0;
}

void LmsDevice::tick(int64_t now_us, int host_baud, Bytes& out)
{
    if (epoch_us_ < 0) epoch_us_ = now_us;
    if (!streaming_) return;
    if (next_scan_us_ == 0) next_scan_us_ = now_us;
    const auto period_us = static_cast<int64_t>(lms::scan_period_s(resolution_cdeg_) * 1e6);
    // The mirror does not wait for the process that emulates it: a tick that comes late sends
    // every scan that fell due meanwhile, each measured and sent at its own time (the host
    // reads them together, as it would after a stall of its own). More than a second behind
    // (the process was stopped), the older scans are dropped, keeping the phase.
    if (now_us - next_scan_us_ > 1'000'000) {
        const int64_t missed = (now_us - next_scan_us_) / period_us;
        stats_.scans_skipped += static_cast<uint64_t>(missed);
        next_scan_us_ += missed * period_us;
    }
    for (; next_scan_us_ <= now_us; next_scan_us_ += period_us) send_scan(next_scan_us_, host_baud, out);
}

void LmsDevice::send_scan(int64_t due_us, int host_baud, Bytes& out)
{
    if (line_free_us_ > due_us) {
        ++stats_.scans_skipped;  // the previous scan is still on the wire
    } else {
        Bytes scan = make_scan(due_us);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        if (options_.faults.bitflip_probability > 0.0 && u(rng_) < options_.faults.bitflip_probability) {
            std::uniform_int_distribution<std::size_t> pos(0, scan.size() - 1);
            std::uniform_int_distribution<int> bit(0, 7);
            scan[pos(rng_)] ^= static_cast<uint8_t>(1u << bit(rng_));
        }
        const std::size_t keep = sim::truncated_length(scan.size(), options_.faults.truncate_probability, rng_);
        if (keep < scan.size()) {
            scan.resize(keep);  // the line cut mid-telegram; the next scan follows as usual
            ++stats_.scans_truncated;
        }
        if (!silent(due_us)) ++stats_.scans_sent;
        send(std::move(scan), host_baud, due_us, out, true);
    }
}

int64_t LmsDevice::next_event_us() const
{
    return streaming_ ? next_scan_us_ : std::numeric_limits<int64_t>::max();
}

}  // namespace ugv::sim::lms
