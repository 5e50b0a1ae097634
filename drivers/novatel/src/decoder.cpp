#include "ugv/novatel/decoder.hpp"

#include <cmath>

#include "sanity.hpp"

namespace ugv::novatel {
namespace {

constexpr double kBitsPerByte = 10.0;  // 8N1: start + 8 data + stop

// The NMEA checks; a NovAtel log's body layout checks its own values (body_layout.hpp).
// NMEA's 8-bit checksum passes one corrupted sentence in 256: a latitude field "40134.57"
// instead of "4013.457" is 401 deg, which would reach the pose filter as a measurement.
bool plausible(const Message& m)
{
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
