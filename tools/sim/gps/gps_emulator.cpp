#include "gps_emulator.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <stdexcept>

#include "ugv/novatel/checksum.hpp"
#include "ugv/novatel/encoding.hpp"
#include "ugv/novatel/enums.hpp"
#include "ugv/novatel/fix_quality.hpp"
#include "ugv/novatel/gps_time.hpp"
#include "ugv/sim/line_faults.hpp"

namespace ugv::sim::gps {
namespace nv = ugv::novatel;
namespace {

constexpr double kEarthRadiusM = 6378137.0;
constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr std::size_t kMaxCommandLine = 256;
constexpr const char* kPrompt = "[COM1]";

std::string upper(std::string s)
{
    for (auto& c : s) {
        c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    }
    return s;
}

bool supported(const std::string& m)
{
    return m == "BESTPOSB" || m == "BESTVELB" || m == "BESTPOSA" || m == "BESTVELA" || m == "GPGGA" ||
           m == "GPRMC" || m == "GPGST";
}

}  // namespace

std::vector<ScriptStep> parse_script(const std::string& text)
{
    std::vector<ScriptStep> steps;
    std::size_t pos = 0;
    while (pos < text.size()) {
        const auto comma = text.find(',', pos);
        const std::string item = text.substr(pos, comma == std::string::npos ? std::string::npos : comma - pos);
        pos = comma == std::string::npos ? text.size() : comma + 1;
        const auto at = item.find('@');
        const uint32_t type = nv::position_type_from_name(upper(item.substr(0, at)));
        if (type == nv::kUnknownEnum) {
            throw std::invalid_argument("unknown position type in '" + item + "'");
        }
        const double t = at == std::string::npos ? 0.0 : std::stod(item.substr(at + 1));
        steps.push_back({t, type});
    }
    if (steps.empty()) {
        throw std::invalid_argument("empty fix script");
    }
    std::sort(steps.begin(), steps.end(), [](const ScriptStep& a, const ScriptStep& b) { return a.at_s < b.at_s; });
    return steps;
}

int gga_quality_of(uint32_t type)
{
    switch (nv::quality_from_position_type(0, type)) {
    case nv::FixQuality::none: return 0;
    case nv::FixQuality::single: return 1;
    case nv::FixQuality::dgps: return 2;
    case nv::FixQuality::sbas: return 9;
    case nv::FixQuality::rtk_fixed: return 4;
    case nv::FixQuality::rtk_float: return 5;
    case nv::FixQuality::dead_reckoning: return 6;
    case nv::FixQuality::unknown: return 7;
    }
    return 0;
}

double sigma_of(uint32_t type)
{
    switch (nv::quality_from_position_type(0, type)) {
    case nv::FixQuality::single: return 1.5;
    case nv::FixQuality::sbas: return 0.8;
    case nv::FixQuality::dgps: return 0.4;
    case nv::FixQuality::rtk_float: return 0.15;
    case nv::FixQuality::rtk_fixed: return 0.02;
    default: return 10.0;
    }
}

GpsEmulator::GpsEmulator(EmulatorConfig config, int64_t start_utime)
    : config_(std::move(config)), start_utime_(start_utime), now_utime_(start_utime), baud_(config_.baud),
      rng_(config_.seed)
{
    if (config_.markov) {
        PositionErrorConfig m = *config_.markov;
        m.scale = config_.noise_scale;
        markov_.emplace(m);
    }
    if (config_.preconfigured) {
        const double period = 1.0 / config_.rate_hz;
        if (config_.protocol == Protocol::novatel) {
            add_log("BESTPOSB", period, start_utime);
            add_log("BESTVELB", period, start_utime);
        } else {
            add_log("GPGGA", period, start_utime);
            add_log("GPRMC", period, start_utime);
            add_log("GPGST", period, start_utime);
        }
    }
    if (config_.garbage_period_s > 0) {
        next_garbage_utime_ = start_utime + static_cast<int64_t>(config_.garbage_period_s * 1e6);
    }
}

uint32_t GpsEmulator::position_type_at(double elapsed_s) const
{
    uint32_t type = config_.script.front().position_type;
    for (const auto& s : config_.script) {
        if (s.at_s <= elapsed_s) {
            type = s.position_type;
        }
    }
    return type;
}

void GpsEmulator::truth(int64_t utime, double& lat, double& lon) const
{
    if (config_.trajectory) {
        const AntennaTruth t = config_.trajectory(utime);
        lat = t.latitude_deg;
        lon = t.longitude_deg;
        return;
    }
    const double d = config_.speed_mps * static_cast<double>(utime - start_utime_) * 1e-6;
    const double h = config_.heading_deg * kDegToRad;
    lat = config_.latitude_deg + d * std::cos(h) / kEarthRadiusM / kDegToRad;
    lon = config_.longitude_deg +
          d * std::sin(h) / (kEarthRadiusM * std::cos(config_.latitude_deg * kDegToRad)) / kDegToRad;
}

std::string GpsEmulator::on_host_bytes(const uint8_t* data, std::size_t n)
{
    std::string out;
    for (std::size_t i = 0; i < n; ++i) {
        const char c = static_cast<char>(data[i]);
        if (c == '\r' || c == '\n') {
            if (!line_.empty()) {
                out += execute(line_);
                line_.clear();
            }
        } else if (line_.size() < kMaxCommandLine) {
            line_ += c;
        }
    }
    bytes_damaged_ += flip_bits(out.begin(), out.end(), config_.bit_error_rate, rng_);
    return out;
}

std::string GpsEmulator::execute(const std::string& line)
{
    ++commands_;
    const nv::Command cmd = nv::parse_command(line);
    const std::string ok = std::string("\r\n<OK\r\n") + kPrompt;
    switch (cmd.type) {
    case nv::Command::Type::unlogall: logs_.clear(); return ok;
    case nv::Command::Type::log:
        if (!supported(cmd.message)) {
            return std::string("\r\n<ERROR:Invalid Message. Field = 2\r\n") + kPrompt;
        }
        if (cmd.trigger != "ONTIME" || cmd.period_s < 0.05) {
            return std::string("\r\n<ERROR:Invalid Message Trigger\r\n") + kPrompt;
        }
        add_log(cmd.message, cmd.period_s, now_utime_);
        return ok;
    case nv::Command::Type::com:
        baud_ = cmd.baud;  // the reply still goes out at the old rate: the caller sends it first
        return ok;
    case nv::Command::Type::unknown: break;
    }
    return std::string("\r\n<ERROR:Invalid Command Name\r\n") + kPrompt;
}

void GpsEmulator::add_log(const std::string& message, double period_s, int64_t now_utime)
{
    const int64_t period_us = std::llround(period_s * 1e6);
    // ONTIME logs fall on multiples of the period in GPS time.
    const int64_t gps_us = now_utime + int64_t{config_.leap_seconds} * 1'000'000;
    const int64_t next_gps = (gps_us / period_us + 1) * period_us;
    logs_.erase(std::remove_if(logs_.begin(), logs_.end(), [&](const ActiveLog& l) { return l.message == message; }),
                logs_.end());
    logs_.push_back({message, period_us, next_gps - int64_t{config_.leap_seconds} * 1'000'000});
}

nv::Position GpsEmulator::position_at(int64_t utime)
{
    const double elapsed = static_cast<double>(utime - start_utime_) * 1e-6;
    nv::Position p;
    uint32_t week = 0, ms = 0;
    nv::unix_utime_to_gps(utime, config_.leap_seconds, week, ms);
    p.header.id = nv::log_id::bestpos;
    p.header.time_status = nv::time_status::finesteering;
    p.header.week = week;
    p.header.ms = ms;
    p.header.idle_percent = 50.0;
    p.position_type = position_type_at(elapsed);
    p.solution_status = p.position_type == nv::position_type::none ? nv::solution_status::insufficient_obs
                                                                   : nv::solution_status::sol_computed;
    double sigma = sigma_of(p.position_type), sigma_height = 1.5 * sigma;
    double lat = 0, lon = 0;
    truth(utime, lat, lon);
    double north = 0, east = 0, up = 0;
    if (markov_) {
        const Ned3 e = markov_->at(utime, p.position_type);
        north = e.north_m;
        east = e.east_m;
        up = e.up_m;
        sigma = markov_->sigma_horizontal_m(p.position_type);
        sigma_height = markov_->sigma_height_m(p.position_type);
    } else if (config_.noise_scale > 0) {
        std::normal_distribution<double> noise(0.0, sigma * config_.noise_scale);
        north = noise(rng_);
        east = noise(rng_);
        up = noise(rng_) * 1.5;
    }
    p.latitude_deg = lat + north / kEarthRadiusM / kDegToRad;
    p.longitude_deg = lon + east / (kEarthRadiusM * std::cos(lat * kDegToRad)) / kDegToRad;
    p.height_msl_m = (config_.trajectory ? config_.trajectory(utime).height_msl_m : config_.height_msl_m) + up;
    p.undulation_m = config_.undulation_m;
    p.datum_id = 61;
    p.sigma_latitude_m = sigma;
    p.sigma_longitude_m = sigma;
    p.sigma_height_m = sigma_height;
    const nv::FixQuality q = nv::quality_from_position_type(p.solution_status, p.position_type);
    const bool diff = q == nv::FixQuality::dgps || q == nv::FixQuality::rtk_fixed || q == nv::FixQuality::rtk_float;
    p.station_id = diff ? "0" : "";
    p.differential_age_s = diff ? 1.0 : 0.0;
    p.solution_age_s = 0.0;
    p.satellites_tracked = 12;
    p.satellites_used = 10;
    return p;
}

nv::Velocity GpsEmulator::velocity_at(int64_t utime)
{
    nv::Velocity v;
    uint32_t week = 0, ms = 0;
    nv::unix_utime_to_gps(utime, config_.leap_seconds, week, ms);
    v.header.id = nv::log_id::bestvel;
    v.header.time_status = nv::time_status::finesteering;
    v.header.week = week;
    v.header.ms = ms;
    v.header.idle_percent = 50.0;
    v.solution_status = nv::solution_status::sol_computed;
    v.velocity_type = position_type_at(static_cast<double>(utime - start_utime_) * 1e-6);
    v.latency_s = 0.15;  // a Doppler velocity is an average over the last interval
    v.age_s = 0.0;
    v.horizontal_speed_mps = config_.speed_mps;
    v.track_deg = config_.heading_deg;
    v.vertical_speed_mps = 0.0;
    if (config_.trajectory) {
        // The Doppler velocity is the average over the last interval: the truth latency ago.
        const AntennaTruth t = config_.trajectory(utime - std::llround(v.latency_s * 1e6));
        v.horizontal_speed_mps = t.horizontal_speed_mps;
        v.track_deg = t.track_deg;
        v.vertical_speed_mps = t.vertical_speed_mps;
    }
    return v;
}

std::string GpsEmulator::emit(const std::string& m, int64_t utime)
{
    if (m == "BESTPOSB" || m == "BESTPOSA") {
        const auto p = position_at(utime);
        if (m == "BESTPOSA") {
            return nv::encode_ascii("BESTPOSA", p.header, nv::position_fields(p));
        }
        const auto f = nv::encode_binary(p.header, nv::encode_position_body(p));
        return {f.begin(), f.end()};
    }
    if (m == "BESTVELB" || m == "BESTVELA") {
        auto v = velocity_at(utime);
        if (m == "BESTVELA") {
            return nv::encode_ascii("BESTVELA", v.header, nv::velocity_fields(v));
        }
        const auto f = nv::encode_binary(v.header, nv::encode_velocity_body(v));
        return {f.begin(), f.end()};
    }
    const double tod_s = static_cast<double>(utime % nv::kUsPerDay) * 1e-6;
    const auto p = position_at(utime);
    if (m == "GPGGA") {
        nv::Gga g;
        g.talker = "GP";
        g.utc_time_s = tod_s;
        g.quality = gga_quality_of(p.position_type);
        g.latitude_deg = p.latitude_deg;
        g.longitude_deg = p.longitude_deg;
        g.satellites_used = p.satellites_used;
        g.hdop = 0.9;
        g.altitude_msl_m = p.height_msl_m;
        g.undulation_m = p.undulation_m;
        if (g.quality == 2 || g.quality == 4 || g.quality == 5) {
            g.differential_age_s = 1.0;
            g.station_id = "0000";
        }
        return nv::encode_nmea(nv::gga_body(g));
    }
    if (m == "GPRMC") {
        nv::Rmc r;
        r.talker = "GP";
        r.utc_time_s = tod_s;
        r.valid = gga_quality_of(p.position_type) > 0;
        r.latitude_deg = p.latitude_deg;
        r.longitude_deg = p.longitude_deg;
        r.speed_mps = config_.speed_mps;
        r.track_deg = config_.heading_deg;
        const int64_t days = utime / nv::kUsPerDay;
        const std::chrono::year_month_day ymd{std::chrono::sys_days{std::chrono::days{days}}};
        r.year = static_cast<int>(ymd.year());
        r.month = static_cast<int>(static_cast<unsigned>(ymd.month()));
        r.day = static_cast<int>(static_cast<unsigned>(ymd.day()));
        return nv::encode_nmea(nv::rmc_body(r));
    }
    // GPGST
    nv::Gst g;
    g.talker = "GP";
    g.utc_time_s = tod_s;
    g.rms_m = p.sigma_latitude_m;
    g.semi_major_m = p.sigma_latitude_m;
    g.semi_minor_m = p.sigma_longitude_m;
    g.orientation_deg = 0.0;
    g.sigma_latitude_m = p.sigma_latitude_m;
    g.sigma_longitude_m = p.sigma_longitude_m;
    g.sigma_altitude_m = p.sigma_height_m;
    return nv::encode_nmea(nv::gst_body(g));
}

std::string GpsEmulator::tick(int64_t now_utime)
{
    now_utime_ = now_utime;
    std::string out;
    const double elapsed = static_cast<double>(now_utime - start_utime_) * 1e-6;
    const bool silent = config_.silence_at_s >= 0 && elapsed >= config_.silence_at_s &&
                        elapsed < config_.silence_at_s + config_.silence_for_s;
    // Emit in time order across logs, as a receiver does within one epoch.
    for (;;) {
        ActiveLog* due = nullptr;
        for (auto& l : logs_) {
            if (l.next_utime <= now_utime && (due == nullptr || l.next_utime < due->next_utime)) {
                due = &l;
            }
        }
        if (due == nullptr) {
            break;
        }
        if (!silent) {
            std::string frame = emit(due->message, due->next_utime);
            const std::size_t keep = truncated_length(frame.size(), config_.truncate_probability, rng_);
            if (keep < frame.size()) {
                frame.resize(keep);  // cut mid-frame; the next frame follows as usual
                ++frames_truncated_;
            }
            out += frame;
        }
        due->next_utime += due->period_us;
        if (due->next_utime + 10 * due->period_us < now_utime) {
            due->next_utime = now_utime;  // far behind (a stalled caller): do not burst
        }
    }
    if (next_garbage_utime_ > 0 && now_utime >= next_garbage_utime_) {
        std::uniform_int_distribution<int> byte(0, 255);
        for (int i = 0; i < 40; ++i) {
            out += static_cast<char>(byte(rng_));
        }
        next_garbage_utime_ += static_cast<int64_t>(config_.garbage_period_s * 1e6);
    }
    if (config_.bit_error_rate <= 0.0) return out;
    const std::string sent = out;
    bytes_damaged_ += flip_bits(out.begin(), out.end(), config_.bit_error_rate, rng_);
    nmea_damage_unseen_ += count_nmea_damage_unseen(sent, out);
    return out;
}

uint64_t count_nmea_damage_unseen(const std::string& sent, const std::string& received)
{
    // NMEA's checksum is the XOR of the bytes between '$' and '*': two flips of the same bit
    // in one sentence cancel. Such a sentence reaches the host changed but valid.
    uint64_t unseen = 0;
    for (std::size_t start = sent.find('$'); start != std::string::npos; start = sent.find('$', start + 1)) {
        const std::size_t star = sent.find('*', start);
        if (star == std::string::npos || star + 3 > sent.size() || star + 3 > received.size()) break;
        if (received.compare(start, star + 3 - start, sent, start, star + 3 - start) == 0) continue;  // intact
        if (received[start] != '$' || received[star] != '*' ||
            received.find('*', start + 1) != star)  // the framing itself was hit: not this sentence
            continue;
        const auto* body = reinterpret_cast<const uint8_t*>(received.data() + start + 1);
        const uint8_t sum = novatel::nmea_checksum(body, star - start - 1);
        char hex[3];
        std::snprintf(hex, sizeof hex, "%02X", sum);
        if (received.compare(star + 1, 2, hex) == 0) ++unseen;
    }
    return unseen;
}

}  // namespace ugv::sim::gps
