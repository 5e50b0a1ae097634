// A receiver port's byte stream (binary, ASCII, NMEA, replies, prompts, garbage), cut into
// chunks the input chooses, through the decoder and interpreter exactly as ugv-gps feeds
// them. Never a crash, and the checks of ReceiverPath hold for every message.
#include <algorithm>

#include "receiver_path.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    if (size == 0) return 0;
    const std::size_t chunk = 1 + data[0] % 128;  // byte 0: the read size
    ugv::fuzz::ReceiverPath path;
    int64_t utime = 1'700'000'000'000'000;
    for (std::size_t at = 1; at < size; at += chunk) {
        utime += 10'000;  // a read every 10 ms
        path.feed(data + at, std::min(chunk, size - at), utime);
    }
    return 0;
}
