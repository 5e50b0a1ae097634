// Raw captures decoded again: the bytes of each RAW_* channel of a log (raw_bytes_t, from the
// device) through the same codec the daemon runs, and what comes out compared, in order, with
// what the daemon published on its channels in the same log.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace ugv::redecode {

struct Options
{
    int gps_baud = 9600;          // ugv-gps `baud` (the arrival fallback's transmission time)
    int gps_leap_seconds = 18;    // ugv-gps `leap_seconds`
    double gps_output_latency_ms = 0.0;
    int imu_command = 0x31;       // ugv-imu `command`: the data frames streamed
};

// One output channel of a raw channel: decoded again vs published.
struct OutputResult
{
    std::string channel;
    uint64_t decoded = 0, published = 0;
    uint64_t matched = 0;            // pairs that agree on every field compared
    uint64_t field_mismatches = 0;   // pairs aligned on their identity whose other fields differ
    uint64_t decoded_only = 0;       // decoded, never published
    uint64_t published_only = 0;     // published, not decoded from the bytes
    std::string fields;              // what is compared
    std::string first_mismatch;      // the first difference, for the reader
    bool ok() const { return field_mismatches == 0 && decoded_only == 0 && published_only == 0; }
};

struct ChannelResult
{
    std::string raw_channel;
    std::string codec;               // "sick_lms2xx", "novatel", "microstrain_gx1", or "" (unknown)
    uint64_t raw_messages = 0, raw_bytes = 0, raw_to_device = 0;
    std::vector<OutputResult> outputs;
    bool ok() const;
};

// Reads the log; throws std::runtime_error when it cannot. Channel pairs by name: RAW_LMS<sfx>
// -> LMS_SCAN<sfx>, RAW_GPS<sfx> -> GPS_FIX<sfx> and GPS_VEL<sfx>, RAW_IMU<sfx> -> IMU<sfx>.
std::vector<ChannelResult> redecode_log(const std::string& path, const Options& options);

std::string to_json(const ChannelResult& r);

}  // namespace ugv::redecode
