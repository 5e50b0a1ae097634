#include "ugv/novatel/decoder.hpp"

#include <cmath>
#include <initializer_list>

namespace ugv::novatel {
namespace {

constexpr double kBitsPerByte = 10.0;  // 8N1: start + 8 data + stop
constexpr double kMaxVelocityLatencyS = 60.0;

bool no_infinity(std::initializer_list<double> values)
{
    for (const double v : values) {
        if (std::isinf(v)) return false;
    }
    return true;
}

// NaN (the field was empty) or a coordinate on the globe.
bool latitude_ok(double deg) { return std::isnan(deg) || (deg >= -90.0 && deg <= 90.0); }
bool longitude_ok(double deg) { return std::isnan(deg) || (deg >= -180.0 && deg <= 180.0); }

// A valid checksum does not make the content sane: NMEA's 8-bit checksum passes one
// corrupted sentence in 256 (a latitude field "40134.57" instead of "4013.457" is 401 deg),
// and a binary double can hold any bit pattern. A position off the globe or an
// infinite value would reach the pose filter as a measurement, so such a frame is malformed.
bool plausible(const Message& m)
{
    // An ASCII header's week is text: the binary header carries it in 16 bits (and a larger
    // one overflows the time stamp).
    const auto week_ok = [](const LogHeader& h) { return h.week <= 0xFFFF; };
    if (const auto* t = std::get_if<TimeLog>(&m)) return week_ok(t->header);
    if (const auto* p = std::get_if<Position>(&m)) {
        if (!week_ok(p->header)) return false;
        // The binary log carries the satellite counts in one byte each.
        const bool counts_ok = p->satellites_tracked >= -1 && p->satellites_tracked <= 255 &&
                               p->satellites_used >= -1 && p->satellites_used <= 255;
        return counts_ok && latitude_ok(p->latitude_deg) && longitude_ok(p->longitude_deg) &&
               no_infinity({p->height_msl_m, p->undulation_m, p->sigma_latitude_m, p->sigma_longitude_m,
                            p->sigma_height_m, p->differential_age_s, p->solution_age_s});
    }
    if (const auto* v = std::get_if<Velocity>(&m)) {
        if (!week_ok(v->header)) return false;
        // The velocity is valid at the time tag minus the latency, so the latency moves the
        // stamp (in integer us): receivers report tens of ms, never a negative one.
        const bool latency_ok = std::isnan(v->latency_s) || (v->latency_s >= 0.0 && v->latency_s <= kMaxVelocityLatencyS);
        return latency_ok && no_infinity({v->age_s, v->horizontal_speed_mps, v->track_deg, v->vertical_speed_mps});
    }
    if (const auto* g = std::get_if<Gga>(&m)) {
        return g->satellites_used >= -1 && g->satellites_used <= 255 && latitude_ok(g->latitude_deg) &&
               longitude_ok(g->longitude_deg);
    }
    if (const auto* r = std::get_if<Rmc>(&m)) return latitude_ok(r->latitude_deg) && longitude_ok(r->longitude_deg);
    return true;
}

}  // namespace

void Decoder::feed(const uint8_t* data, std::size_t n, int64_t chunk_utime, const Sink& sink)
{
    const uint64_t chunk_end = splitter_.bytes_fed() + n;
    splitter_.feed(data, n, [&](const FrameView& f) { on_frame(f, chunk_end, chunk_utime, sink); });
}

void Decoder::on_frame(const FrameView& f, uint64_t chunk_end, int64_t chunk_utime, const Sink& sink)
{
    int64_t arrival = chunk_utime;
    if (baud_ > 0 && chunk_end > f.end_offset) {
        const double after_s = static_cast<double>(chunk_end - f.end_offset) * kBitsPerByte / baud_;
        arrival -= std::llround(after_s * 1e6);
    }
    DecodeStatus status = DecodeStatus::unknown;
    switch (f.kind) {
    case FrameKind::binary:
    case FrameKind::binary_short: {
        uint16_t id = 0;
        status = decode_binary(f.data, f.size, f.kind, scratch_, id);
        if (status == DecodeStatus::unknown) {
            ++counters_.unknown_binary_ids[id];
        }
        break;
    }
    case FrameKind::ascii:
    case FrameKind::ascii_short:
    case FrameKind::nmea: {
        std::string_view name;
        status = f.kind == FrameKind::nmea ? decode_nmea(f.data, f.size, scratch_, name)
                                           : decode_ascii(f.data, f.size, f.kind, scratch_, name);
        if (status == DecodeStatus::unknown) {
            ++counters_.unknown_names[std::string(name)];
        }
        break;
    }
    case FrameKind::reply:
    case FrameKind::prompt: {
        Reply r;
        r.kind = f.kind;
        const std::size_t skip = f.kind == FrameKind::reply ? 1 : 0;
        r.text.assign(reinterpret_cast<const char*>(f.data) + skip, f.size - skip);
        scratch_ = std::move(r);
        status = DecodeStatus::decoded;
        break;
    }
    }
    if (status == DecodeStatus::decoded && !plausible(scratch_)) {
        status = DecodeStatus::malformed;
    }
    switch (status) {
    case DecodeStatus::decoded:
        ++counters_.decoded;
        sink(Decoded{scratch_, f.kind, arrival, f.size});
        break;
    case DecodeStatus::response: ++counters_.binary_responses; break;
    case DecodeStatus::unknown: ++counters_.unknown_total; break;
    case DecodeStatus::malformed: ++counters_.malformed; break;
    }
}

}  // namespace ugv::novatel
