#include "ugv/novatel/interpreter.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "ugv/novatel/enums.hpp"

namespace ugv::novatel {
namespace {

constexpr double kBitsPerByte = 10.0;  // 8N1
constexpr double kDegToRad = std::numbers::pi / 180.0;
constexpr double kSameEpochS = 0.0005;  // NMEA times of one epoch agree to the printed digit

// A log's rank among the sources of its quantity, from the log table. A message the table
// lacks (built by hand) ranks with the worst log of the table.
int rank_of(uint16_t id)
{
    if (const LogInfo* log = find_log(id)) return log->rank;
    int worst = 0;
    for (const auto& log : log_table()) worst = std::max(worst, log.rank);
    return worst;
}

Source source_of(FrameKind kind)
{
    switch (kind) {
    case FrameKind::binary:
    case FrameKind::binary_short: return Source::novatel_binary;
    case FrameKind::nmea: return Source::nmea;
    default: return Source::novatel_ascii;
    }
}

bool differential(FixQuality q)
{
    return q == FixQuality::dgps || q == FixQuality::sbas || q == FixQuality::rtk_float ||
           q == FixQuality::rtk_fixed;
}

int32_t raw_enum(uint32_t v) { return v == kUnknownEnum ? -1 : static_cast<int32_t>(v); }

bool same_epoch(double a_s, double b_s) { return std::fabs(a_s - b_s) < kSameEpochS; }

}  // namespace

int64_t Interpreter::fallback_utime(int64_t arrival_utime, std::size_t frame_bytes) const
{
    int64_t t = arrival_utime - config_.output_latency_us;
    if (config_.baud > 0) {
        // arrival_utime is the last byte's; the receiver started sending at the first.
        t -= std::llround(static_cast<double>(frame_bytes) * kBitsPerByte / config_.baud * 1e6);
    }
    return t;
}

bool Interpreter::accept(int rank, int64_t arrival_utime, SourceTimes& last_seen)
{
    const auto r = static_cast<std::size_t>(rank);
    for (std::size_t better = 0; better < r; ++better) {
        if (last_seen[better] != 0 && arrival_utime - last_seen[better] < config_.source_hold_us) {
            ++superseded_;
            return false;
        }
    }
    last_seen[r] = arrival_utime;
    return true;
}

Interpretation Interpreter::on_message(const Message& message, FrameKind kind, int64_t arrival,
                                       std::size_t bytes)
{
    Interpretation out;
    if (const auto* p = std::get_if<Position>(&message)) {
        last_time_status_ = p->header.time_status;
        if (accept(rank_of(p->header.id), arrival, position_seen_)) {
            out.fix = fix_from_position(*p, kind, arrival, bytes);
        }
    } else if (const auto* v = std::get_if<Velocity>(&message)) {
        last_time_status_ = v->header.time_status;
        if (accept(rank_of(v->header.id), arrival, velocity_seen_)) {
            out.velocity = velocity_from_log(*v, kind, arrival, bytes);
        }
    } else if (const auto* t = std::get_if<TimeLog>(&message)) {
        last_time_status_ = t->header.time_status;
    } else if (const auto* gga = std::get_if<Gga>(&message)) {
        return on_gga(*gga, arrival, bytes);
    } else if (const auto* gst = std::get_if<Gst>(&message)) {
        return on_gst(*gst);
    } else if (const auto* rmc = std::get_if<Rmc>(&message)) {
        return on_nmea_velocity(rmc->utc_time_s, rmc->valid, rmc->speed_mps, rmc->track_deg, nmea_rank::rmc, arrival,
                                bytes);
    } else if (const auto* vtg = std::get_if<Vtg>(&message)) {
        return on_nmea_velocity(kNaN, false, vtg->speed_mps, vtg->track_deg, nmea_rank::vtg, arrival, bytes);
    }
    return out;
}

Fix Interpreter::fix_from_position(const Position& p, FrameKind kind, int64_t arrival, std::size_t bytes)
{
    Fix f;
    const LogHeader& h = p.header;
    f.source = source_of(kind);
    f.gps_week = static_cast<int32_t>(h.week);
    f.gps_ms = static_cast<int32_t>(h.ms);
    f.time_from_receiver = time_status_is_fine(h.time_status);
    if (f.time_from_receiver) {
        f.utime = gps_to_unix_utime(h.week, h.ms, config_.leap_seconds);
        clock_.update(arrival, f.utime);
        host_clock_.update(fallback_utime(arrival, bytes), f.utime);
    } else {
        f.utime = fallback_utime(arrival, bytes);
    }
    f.latitude_deg = p.latitude_deg;
    f.longitude_deg = p.longitude_deg;
    f.undulation_m = p.undulation_m;
    f.height_m = p.height_msl_m + p.undulation_m;
    f.sigma_latitude_m = p.sigma_latitude_m;
    f.sigma_longitude_m = p.sigma_longitude_m;
    f.sigma_height_m = p.sigma_height_m;
    f.solution_status = raw_enum(p.solution_status);
    f.position_type = raw_enum(p.position_type);
    f.quality = quality_from_position_type(p.solution_status, p.position_type);
    f.satellites_used = p.satellites_used;
    f.satellites_tracked = p.satellites_tracked;
    f.differential_age_s = differential(f.quality) ? p.differential_age_s : kNaN;
    return f;
}

VelocityFix Interpreter::velocity_from_log(const Velocity& v, FrameKind kind, int64_t arrival, std::size_t bytes)
{
    VelocityFix out;
    const LogHeader& h = v.header;
    out.source = source_of(kind);
    out.time_from_receiver = time_status_is_fine(h.time_status);
    const double latency_s = std::isfinite(v.latency_s) ? v.latency_s : 0.0;
    const int64_t latency_us = std::llround(latency_s * 1e6);
    out.utime = (out.time_from_receiver ? gps_to_unix_utime(h.week, h.ms, config_.leap_seconds)
                                        : fallback_utime(arrival, bytes)) -
                latency_us;
    out.horizontal_speed_mps = v.horizontal_speed_mps;
    out.track_rad = v.track_deg * kDegToRad;
    out.vertical_speed_mps = v.vertical_speed_mps;
    out.latency_s = v.latency_s;
    out.solution_status = raw_enum(v.solution_status);
    out.velocity_type = raw_enum(v.velocity_type);
    return out;
}

Fix Interpreter::fix_from_gga(const Gga& g, int64_t arrival, std::size_t bytes)
{
    Fix f;
    f.source = Source::nmea;
    f.quality = quality_from_gga(g.quality);
    // A receiver with a fix knows GPS time; the GGA time is then the measurement time.
    f.time_from_receiver = g.quality > 0 && std::isfinite(g.utc_time_s);
    if (f.time_from_receiver) {
        f.utime = utc_time_of_day_to_utime(g.utc_time_s, arrival);
        clock_.update(arrival, f.utime);
        host_clock_.update(fallback_utime(arrival, bytes), f.utime);
        uint32_t week = 0, ms = 0;
        unix_utime_to_gps(f.utime, config_.leap_seconds, week, ms);
        f.gps_week = static_cast<int32_t>(week);
        f.gps_ms = static_cast<int32_t>(ms);
    } else {
        f.utime = fallback_utime(arrival, bytes);
    }
    f.latitude_deg = g.latitude_deg;
    f.longitude_deg = g.longitude_deg;
    f.undulation_m = g.undulation_m;
    f.height_m = g.altitude_msl_m + g.undulation_m;
    f.position_type = g.quality;
    f.satellites_used = g.satellites_used;
    f.differential_age_s = differential(f.quality) ? g.differential_age_s : kNaN;
    return f;
}

void Interpreter::attach_gst(Fix& fix, const Gst& gst) const
{
    fix.sigma_latitude_m = gst.sigma_latitude_m;
    fix.sigma_longitude_m = gst.sigma_longitude_m;
    fix.sigma_height_m = gst.sigma_altitude_m;
}

Interpretation Interpreter::on_gga(const Gga& g, int64_t arrival, std::size_t bytes)
{
    Interpretation out;
    if (!accept(nmea_rank::gga, arrival, position_seen_)) {
        return out;
    }
    Fix fix = fix_from_gga(g, arrival, bytes);
    if (!gst_seen_) {
        out.fix = fix;  // this receiver sends no GST: publish at once
        return out;
    }
    if (last_gst_ && same_epoch(last_gst_->utc_time_s, g.utc_time_s)) {
        attach_gst(fix, *last_gst_);  // the GST of this epoch came first
        out.fix = fix;
        return out;
    }
    // Wait for this epoch's GST; a previous GGA still waiting goes out without one.
    out.fix = std::move(pending_gga_);
    pending_gga_ = fix;
    pending_gga_utc_s_ = g.utc_time_s;
    return out;
}

Interpretation Interpreter::on_gst(const Gst& g)
{
    Interpretation out;
    gst_seen_ = true;
    last_gst_ = g;
    if (pending_gga_ && same_epoch(pending_gga_utc_s_, g.utc_time_s)) {
        attach_gst(*pending_gga_, g);
        out.fix = std::move(pending_gga_);
        pending_gga_.reset();
    }
    return out;
}

Interpretation Interpreter::on_nmea_velocity(double utc_s, bool fix_valid, double speed_mps, double track_deg,
                                             int rank, int64_t arrival, std::size_t bytes)
{
    Interpretation out;
    if (!accept(rank, arrival, velocity_seen_)) {
        return out;
    }
    VelocityFix v;
    v.source = Source::nmea;
    v.time_from_receiver = fix_valid && std::isfinite(utc_s);
    v.utime = v.time_from_receiver ? utc_time_of_day_to_utime(utc_s, arrival) : fallback_utime(arrival, bytes);
    v.horizontal_speed_mps = speed_mps;
    v.track_rad = track_deg * kDegToRad;
    v.solution_status = fix_valid ? 0 : -1;
    out.velocity = v;
    return out;
}

}  // namespace ugv::novatel
