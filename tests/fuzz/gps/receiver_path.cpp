#include "receiver_path.hpp"

#include <cmath>
#include <cstdlib>

namespace ugv::fuzz {
namespace {

void require(bool ok)
{
    if (!ok) std::abort();
}

// The documented value convention: a number, or NaN for a field the frame left empty.
// Never an infinity (the pose filter would take it as a measurement).
bool finite_or_nan(double v) { return !std::isinf(v); }

bool latitude_ok(double deg) { return std::isnan(deg) || (deg >= -90.0 && deg <= 90.0); }
bool longitude_ok(double deg) { return std::isnan(deg) || (deg >= -180.0 && deg <= 180.0); }

void check_fix(const novatel::Fix& f, int64_t chunk_utime)
{
    require(latitude_ok(f.latitude_deg) && longitude_ok(f.longitude_deg));
    for (double v : {f.height_m, f.undulation_m, f.sigma_latitude_m, f.sigma_longitude_m, f.sigma_height_m,
                     f.differential_age_s}) {
        require(finite_or_nan(v));
    }
    require(f.satellites_used >= -1 && f.satellites_tracked >= -1);
    // A time that is not the receiver's is derived from the arrival: never in the future.
    if (!f.time_from_receiver) require(f.utime <= chunk_utime);
}

void check_velocity(const novatel::VelocityFix& v, int64_t chunk_utime)
{
    for (double x : {v.horizontal_speed_mps, v.track_rad, v.vertical_speed_mps, v.latency_s}) require(finite_or_nan(x));
    if (!v.time_from_receiver) require(v.utime <= chunk_utime);
}

}  // namespace

void ReceiverPath::feed(const uint8_t* data, std::size_t n, int64_t chunk_utime)
{
    fed_ += n;
    decoder_.feed(data, n, chunk_utime, [&](const novatel::Decoded& m) { on_message(m, chunk_utime); });
    const auto& s = decoder_.splitter_counters();
    // Every byte is either in a frame, skipped, a line end or still buffered: no count runs
    // ahead of the bytes fed, and no frame is handed out twice.
    require(s.skipped_bytes <= fed_ && s.frames_total() <= fed_ && messages_ <= s.frames_total());
}

void ReceiverPath::on_message(const novatel::Decoded& m, int64_t chunk_utime)
{
    ++messages_;
    require(m.frame_bytes > 0 && m.frame_bytes <= fed_);
    require(m.arrival_utime <= chunk_utime);
    const auto out = interpreter_.on_message(m.message, m.kind, m.arrival_utime, m.frame_bytes);
    if (out.fix) check_fix(*out.fix, chunk_utime);
    if (out.velocity) check_velocity(*out.velocity, chunk_utime);
}

}  // namespace ugv::fuzz
