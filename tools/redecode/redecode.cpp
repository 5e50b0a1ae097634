#include "ugv/redecode/redecode.hpp"

#include <cmath>
#include <cstring>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <utility>

#include <spdlog/fmt/fmt.h>

#include "ugv/bus/bus.hpp"
#include "ugv/bus/typed.hpp"
#include "ugv/gps_fix_t.hpp"
#include "ugv/gps_velocity_t.hpp"
#include "ugv/imu_t.hpp"
#include "ugv/laser_scan_t.hpp"
#include "ugv/microstrain_gx1/frame_parser.hpp"
#include "ugv/microstrain_gx1/protocol.hpp"
#include "ugv/novatel/decoder.hpp"
#include "ugv/novatel/interpreter.hpp"
#include "ugv/raw_bytes_t.hpp"
#include "ugv/sick_lms2xx/decoder.hpp"
#include "ugv/sick_lms2xx/scan.hpp"

namespace ugv::redecode {

namespace {

bool same_double(double a, double b) { return (std::isnan(a) && std::isnan(b)) || a == b; }

// Aligns what was decoded with what was published, both in log order: equal identities pair
// up; a record of one side with no partner within kLookahead of the other is that side's only.
// Paired records are then compared field by field (diff: "" when equal, else what differs).
template <class D, class P>
void align(const std::vector<D>& dec, const std::vector<P>& pub, OutputResult& r,
           const std::function<bool(const D&, const P&)>& same, const std::function<std::string(const D&, const P&)>& diff)
{
    constexpr std::size_t kLookahead = 16;
    r.decoded = dec.size();
    r.published = pub.size();
    std::size_t i = 0, j = 0;
    const auto note = [&](const char* side, std::size_t at, std::size_t of) {
        if (r.first_mismatch.empty()) r.first_mismatch = fmt::format("{} record {} of {} has no partner", side, at, of);
    };
    const auto pair = [&](const D& d, const P& p) {
        const std::string why = diff(d, p);
        if (why.empty()) {
            ++r.matched;
        } else {
            ++r.field_mismatches;
            if (r.first_mismatch.empty()) r.first_mismatch = why;
        }
    };
    while (i < dec.size() && j < pub.size()) {
        if (same(dec[i], pub[j])) {
            pair(dec[i++], pub[j++]);
            continue;
        }
        std::size_t k = 1;
        while (k <= kLookahead && j + k < pub.size() && !same(dec[i], pub[j + k])) ++k;
        if (k <= kLookahead && j + k < pub.size()) {
            note("published", j, pub.size());
            r.published_only += k;
            j += k;
            continue;
        }
        k = 1;
        while (k <= kLookahead && i + k < dec.size() && !same(dec[i + k], pub[j])) ++k;
        if (k <= kLookahead && i + k < dec.size()) {
            note("decoded", i, dec.size());
            r.decoded_only += k;
            i += k;
            continue;
        }
        note("decoded", i, dec.size());
        ++r.decoded_only;
        ++r.published_only;
        ++i;
        ++j;
    }
    if (i < dec.size()) note("decoded", i, dec.size());
    if (j < pub.size()) note("published", j, pub.size());
    r.decoded_only += dec.size() - i;
    r.published_only += pub.size() - j;
}

// --- GPS: novatel::Decoder + Interpreter, as ugv-gps runs them.
struct GpsChannel
{
    novatel::Decoder decoder;
    novatel::Interpreter interpreter;
    std::vector<novatel::Fix> fixes;
    std::vector<novatel::VelocityFix> velocities;
    explicit GpsChannel(const Options& o)
        : interpreter(novatel::InterpreterConfig{o.gps_leap_seconds, std::llround(o.gps_output_latency_ms * 1000.0),
                                                 o.gps_baud, 2'000'000})
    {
        decoder.set_baud(o.gps_baud);
    }
    void feed(const raw_bytes_t& m)
    {
        decoder.feed(m.data.data(), m.data.size(), m.utime, [this](const novatel::Decoded& d) {
            const auto out = interpreter.on_message(d.message, d.kind, d.arrival_utime, d.frame_bytes);
            if (out.fix) fixes.push_back(*out.fix);
            if (out.velocity) velocities.push_back(*out.velocity);
        });
    }
};

std::string fix_diff(const novatel::Fix& d, const gps_fix_t& p)
{
    if (d.gps_week != p.gps_week || d.gps_ms != p.gps_ms) return fmt::format("fix {}: GPS week/ms {}/{} vs {}/{}", p.utime, d.gps_week, d.gps_ms, p.gps_week, p.gps_ms);
    if (!same_double(d.latitude_deg, p.latitude) || !same_double(d.longitude_deg, p.longitude) || !same_double(d.height_m, p.height))
        return fmt::format("fix {}: position {:.9f} {:.9f} {:.3f} vs {:.9f} {:.9f} {:.3f}", p.utime, d.latitude_deg,
                           d.longitude_deg, d.height_m, p.latitude, p.longitude, p.height);
    if (static_cast<int8_t>(d.quality) != p.fix_quality || static_cast<int8_t>(d.source) != p.source ||
        d.position_type != p.position_type || d.solution_status != p.solution_status)
        return fmt::format("fix {}: quality/source/type/status differ", p.utime);
    if (!same_double(static_cast<float>(d.sigma_latitude_m), p.sigma_latitude) ||
        !same_double(static_cast<float>(d.sigma_longitude_m), p.sigma_longitude) ||
        !same_double(static_cast<float>(d.sigma_height_m), p.sigma_height))
        return fmt::format("fix {}: sigmas differ", p.utime);
    return "";
}

std::string velocity_diff(const novatel::VelocityFix& d, const gps_velocity_t& p)
{
    if (!same_double(d.horizontal_speed_mps, p.horizontal_speed) || !same_double(d.track_rad, p.track) ||
        !same_double(d.vertical_speed_mps, p.vertical_speed))
        return fmt::format("velocity {}: {} {} {} vs {} {} {}", p.utime, d.horizontal_speed_mps, d.track_rad,
                           d.vertical_speed_mps, p.horizontal_speed, p.track, p.vertical_speed);
    return "";
}

// --- LMS: the telegram decoder and decode_scan, as ugv-lms runs them.
struct LmsChannel
{
    sick_lms2xx::Decoder decoder;
    std::vector<sick_lms2xx::Scan> scans;
    void feed(const raw_bytes_t& m)
    {
        decoder.feed(m.data.data(), m.data.size(), [this](const sick_lms2xx::DecoderEvent& e) {
            if (e.kind != sick_lms2xx::DecoderEvent::Kind::telegram) return;
            sick_lms2xx::Scan s;
            if (sick_lms2xx::decode_scan(e.telegram, s) == sick_lms2xx::ScanError::none) scans.push_back(std::move(s));
        });
    }
};

bool same_beams(const sick_lms2xx::Scan& d, const laser_scan_t& p)
{
    if (d.ranges_m.size() != p.ranges.size() || d.flags != p.flags) return false;
    for (std::size_t k = 0; k < d.ranges_m.size(); ++k)
        if (!same_double(d.ranges_m[k], p.ranges[k])) return false;
    return true;
}

// --- IMU: the GX1 frame parser; a frame is known by its device timer word. As the session
// does, the start of continuous mode (10 00 cmd sent) is confirmed by the echo or, when the
// echo was damaged, by the first data frame, which is then not a sample; and the first sample
// of a stream waits for the second (SamplePlausibility) and is never published.
struct ImuChannel
{
    microstrain_gx1::FrameParser parser;
    std::vector<microstrain_gx1::Frame> frames;
    uint8_t command;
    bool starting = false, first = false;
    explicit ImuChannel(int c) : command(static_cast<uint8_t>(c)) { parser.accept_only({command}); }
    void sent(const raw_bytes_t& m)
    {
        if (m.data == microstrain_gx1::encode_start_continuous(command)) {
            starting = true;
            parser.accept_only({microstrain_gx1::cmd::continuous, command});
        }
    }
    void feed(const raw_bytes_t& m)
    {
        parser.feed(m.data.data(), m.data.size(), m.utime);
        microstrain_gx1::Frame f;
        while (parser.next(f)) {
            if (starting) {
                if (f.command == command || (f.command == microstrain_gx1::cmd::continuous && (f.words[0] & 0xFF) == command)) {
                    starting = false;
                    first = true;
                    parser.accept_only({command});
                }
                continue;
            }
            if (f.command != command) continue;
            if (!std::exchange(first, false)) frames.push_back(f);
        }
    }
};

struct RawChannel
{
    ChannelResult result;
    std::string suffix;
    std::unique_ptr<GpsChannel> gps;
    std::unique_ptr<LmsChannel> lms;
    std::unique_ptr<ImuChannel> imu;
};

bool starts_with(const std::string& s, const std::string& p) { return s.rfind(p, 0) == 0; }

OutputResult output(std::string channel, std::string fields)
{
    OutputResult r;
    r.channel = std::move(channel);
    r.fields = std::move(fields);
    return r;
}

}  // namespace

bool ChannelResult::ok() const
{
    if (codec.empty() || outputs.empty()) return false;
    for (const auto& o : outputs)
        if (!o.ok()) return false;
    return true;
}

std::vector<ChannelResult> redecode_log(const std::string& path, const Options& options)
{
    std::unique_ptr<bus::Bus> log;
    try {
        log = bus::open_log_replay(path);
    } catch (const std::exception& e) {
        throw std::runtime_error(e.what());
    }
    std::map<std::string, RawChannel> raws;  // by channel name, in name order
    std::map<std::string, std::vector<gps_fix_t>> fixes;
    std::map<std::string, std::vector<gps_velocity_t>> velocities;
    std::map<std::string, std::vector<laser_scan_t>> scans;
    std::map<std::string, std::vector<imu_t>> imus;

    bus::subscribe<raw_bytes_t>(*log, "RAW_.*", [&](const std::string& ch, const raw_bytes_t& m, int64_t) {
        auto [it, fresh] = raws.try_emplace(ch);
        RawChannel& rc = it->second;
        if (fresh) {
            rc.result.raw_channel = ch;
            for (const auto& [prefix, codec] : {std::pair<std::string, std::string>{"RAW_LMS", "sick_lms2xx"},
                                                {"RAW_GPS", "novatel"}, {"RAW_IMU", "microstrain_gx1"}}) {
                if (!starts_with(ch, prefix)) continue;
                rc.result.codec = codec;
                rc.suffix = ch.substr(prefix.size());
            }
            if (rc.result.codec == "novatel") rc.gps = std::make_unique<GpsChannel>(options);
            if (rc.result.codec == "sick_lms2xx") rc.lms = std::make_unique<LmsChannel>();
            if (rc.result.codec == "microstrain_gx1") rc.imu = std::make_unique<ImuChannel>(options.imu_command);
        }
        ++rc.result.raw_messages;
        rc.result.raw_bytes += m.data.size();
        if (m.direction == raw_bytes_t::DIRECTION_TO_DEVICE) {
            ++rc.result.raw_to_device;
            if (rc.imu) rc.imu->sent(m);
            return;  // otherwise the codecs read what the device sent
        }
        if (rc.gps) rc.gps->feed(m);
        if (rc.lms) rc.lms->feed(m);
        if (rc.imu) rc.imu->feed(m);
    });
    bus::subscribe<gps_fix_t>(*log, "GPS_FIX.*", [&](const std::string& ch, const gps_fix_t& m, int64_t) { fixes[ch].push_back(m); });
    bus::subscribe<gps_velocity_t>(*log, "GPS_VEL.*",
                                   [&](const std::string& ch, const gps_velocity_t& m, int64_t) { velocities[ch].push_back(m); });
    bus::subscribe<laser_scan_t>(*log, "LMS_SCAN.*", [&](const std::string& ch, const laser_scan_t& m, int64_t) { scans[ch].push_back(m); });
    bus::subscribe<imu_t>(*log, "IMU.*", [&](const std::string& ch, const imu_t& m, int64_t) { imus[ch].push_back(m); });
    while (log->handle(0) == bus::HandleResult::handled) {
    }

    std::vector<ChannelResult> out;
    for (auto& [ch, rc] : raws) {
        ChannelResult& r = rc.result;
        if (rc.gps) {
            OutputResult f = output("GPS_FIX" + rc.suffix, "utime (identity), GPS week and ms, latitude, longitude, height, sigmas, quality, source, type, status");
            align<novatel::Fix, gps_fix_t>(
                rc.gps->fixes, fixes[f.channel], f, [](const novatel::Fix& d, const gps_fix_t& p) { return d.utime == p.utime; },
                fix_diff);
            OutputResult v = output("GPS_VEL" + rc.suffix, "utime (identity), horizontal speed, track, vertical speed");
            align<novatel::VelocityFix, gps_velocity_t>(
                rc.gps->velocities, velocities[v.channel], v,
                [](const novatel::VelocityFix& d, const gps_velocity_t& p) { return d.utime == p.utime; }, velocity_diff);
            r.outputs = {f, v};
        } else if (rc.lms) {
            OutputResult s = output("LMS_SCAN" + rc.suffix, "device scan index (identity, else the beams), ranges, flags");
            align<sick_lms2xx::Scan, laser_scan_t>(
                rc.lms->scans, scans[s.channel], s,
                [](const sick_lms2xx::Scan& d, const laser_scan_t& p) {
                    return d.scan_index >= 0 && p.device_scan_counter >= 0 ? d.scan_index == p.device_scan_counter
                                                                           : same_beams(d, p);
                },
                [](const sick_lms2xx::Scan& d, const laser_scan_t& p) {
                    return same_beams(d, p) ? std::string()
                                            : fmt::format("scan index {}: ranges or flags differ", p.device_scan_counter);
                });
            r.outputs = {s};
        } else if (rc.imu) {
            OutputResult s = output("IMU" + rc.suffix, "device timer (identity: the low 16 bits of device_ticks)");
            align<microstrain_gx1::Frame, imu_t>(
                rc.imu->frames, imus[s.channel], s,
                [](const microstrain_gx1::Frame& d, const imu_t& p) {
                    return d.ticks() == static_cast<uint16_t>(p.device_ticks & 0xFFFF);
                },
                [](const microstrain_gx1::Frame&, const imu_t&) { return std::string(); });
            r.outputs = {s};
        }
        out.push_back(std::move(r));
    }
    return out;
}

namespace {
std::string json_string(const std::string& s)
{
    std::string o = "\"";
    for (const char c : s) {
        if (c == '"' || c == '\\') {
            o += '\\';
            o += c;
        } else if (static_cast<unsigned char>(c) < 0x20) {
            o += fmt::format("\\u{:04x}", static_cast<int>(static_cast<unsigned char>(c)));
        } else {
            o += c;
        }
    }
    return o + "\"";
}
}  // namespace

std::string to_json(const ChannelResult& r)
{
    std::string o = fmt::format("{{\"raw_channel\":{},\"codec\":{},\"raw_messages\":{},\"raw_bytes\":{},\"raw_to_device\":{},\"outputs\":[",
                                json_string(r.raw_channel), r.codec.empty() ? "null" : json_string(r.codec), r.raw_messages,
                                r.raw_bytes, r.raw_to_device);
    for (std::size_t k = 0; k < r.outputs.size(); ++k) {
        const OutputResult& x = r.outputs[k];
        o += fmt::format("{}{{\"channel\":{},\"decoded\":{},\"published\":{},\"matched\":{},\"field_mismatches\":{},"
                         "\"decoded_only\":{},\"published_only\":{},\"fields\":{}{}}}",
                         k ? "," : "", json_string(x.channel), x.decoded, x.published, x.matched, x.field_mismatches,
                         x.decoded_only, x.published_only, json_string(x.fields),
                         x.first_mismatch.empty() ? "" : ",\"first_mismatch\":" + json_string(x.first_mismatch));
    }
    return o + fmt::format("],\"ok\":{}}}", r.ok() ? "true" : "false");
}

}  // namespace ugv::redecode
