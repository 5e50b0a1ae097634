// The GX1 reply stream as the session reads it: any bytes, cut into reads the input chooses
// (each read ~1 ms after the last, at 38400 baud), through the frame parser, each verified
// frame through SamplePath. Never a crash; every byte fed is accounted for exactly once
// (in a frame, skipped, or still buffered), and what stays buffered is less than one reply.
#include <algorithm>
#include <cstdlib>

#include "sample_path.hpp"
#include "ugv/microstrain_gx1/protocol.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    using namespace ugv::microstrain_gx1;
    if (size < 2) return 0;
    const std::size_t chunk = 1 + data[0] % 64;  // byte 0: the read size
    FrameParser parser(10.0 * 1e6 / 38400.0);
    // Byte 1 odd: the session's streaming setting (only its command starts a frame).
    if (data[1] & 1) parser.accept_only({data[1] & 0x80 ? cmd::stab_quaternion_vectors : cmd::stab_euler_accel_rate});
    ugv::fuzz::SamplePath path;
    uint64_t framed_bytes = 0;
    int64_t utime = 1'700'000'000'000'000;
    const std::size_t n = size - 2;
    for (std::size_t at = 0; at < n; at += chunk) {
        utime += 1000;
        parser.feed(data + 2 + at, std::min(chunk, n - at), utime);
        Frame f;
        while (parser.next(f)) {
            framed_bytes += reply_length(f.command);
            path.on_frame(f);
        }
    }
    const ParserCounters& c = parser.counters();
    if (framed_bytes + c.bytes_skipped + parser.buffered() != n) std::abort();
    // next() stops only at an incomplete candidate: less than the longest reply is left.
    if (parser.buffered() >= max_reply_length) std::abort();
    return 0;
}
