// The LMS byte stream as the session reads it: any bytes, cut into chunks at points the input
// chooses, into the host-side telegram decoder. Never a crash; every telegram it delivers
// satisfies check_telegram; its counters add up (every byte is buffered, delivered or
// skipped, so nothing is counted twice and the buffer never holds more than one frame).
#include <cstdlib>

#include "scan_invariants.hpp"
#include "ugv/sick_lms2xx/decoder.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    using namespace ugv::sick_lms2xx;
    if (size == 0) return 0;
    // Byte 0 chooses the chunk length (1..64), the rest is the stream.
    const std::size_t chunk = 1 + data[0] % 64;
    const uint8_t* stream = data + 1;
    const std::size_t n = size - 1;

    Decoder decoder(kDeviceAddress);
    uint64_t delivered_bytes = 0, answers = 0;
    const auto handler = [&](const DecoderEvent& e) {
        if (e.kind == DecoderEvent::Kind::telegram) {
            ugv::fuzz::check_telegram(e.telegram);
            delivered_bytes += e.telegram.raw.size();
        } else if (e.kind == DecoderEvent::Kind::ack || e.kind == DecoderEvent::Kind::nak) {
            ++answers;
        }
    };
    for (std::size_t at = 0; at < n; at += chunk) decoder.feed(stream + at, std::min(chunk, n - at), handler);

    const DecoderStats& s = decoder.stats();
    if (s.bytes_in != n) std::abort();
    if (delivered_bytes + answers + s.skipped_bytes + decoder.buffered() != n) std::abort();
    if (decoder.buffered() > kHeaderBytes + kMaxLen + kCrcBytes) std::abort();
    return 0;
}
