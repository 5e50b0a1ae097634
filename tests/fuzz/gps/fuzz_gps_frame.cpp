// One frame of any content behind a valid checksum, so the fuzzer gets past the CRC into the
// binary, ASCII and NMEA log decoders and the interpreter. Byte 0 chooses the framing:
//   0 binary long header: the rest is header + body; sync, header length (28) and message
//     length are set so that it frames
//   1 binary short header: the same with AA 44 13 and a 12-byte header
//   2 '#' ASCII log, 3 '%' short ASCII log, 4 '$' NMEA: the rest is the text between the
//     start character and '*', and the target appends the checksum and CR LF
// A frame built this way must come out of the splitter as that kind when its text has no
// framing characters in it; whatever comes out must pass ReceiverPath's checks.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "receiver_path.hpp"
#include "ugv/novatel/checksum.hpp"

namespace {

void put_u32le(std::vector<uint8_t>& out, uint32_t v)
{
    for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
}

std::vector<uint8_t> binary_frame(const uint8_t* p, std::size_t n, bool long_header)
{
    const std::size_t header = long_header ? 28 : 12;
    std::vector<uint8_t> f(p, p + n);
    if (f.size() < header) f.resize(header, 0);
    const std::size_t body = std::min<std::size_t>(f.size() - header, long_header ? 4096 : 255);
    f.resize(header + body);
    f[0] = 0xAA;
    f[1] = 0x44;
    f[2] = long_header ? 0x12 : 0x13;
    if (long_header) {
        f[3] = static_cast<uint8_t>(header);
        f[8] = static_cast<uint8_t>(body & 0xff);
        f[9] = static_cast<uint8_t>(body >> 8);
    } else {
        f[3] = static_cast<uint8_t>(body);
    }
    put_u32le(f, ugv::novatel::crc32(f.data(), f.size()));
    return f;
}

std::vector<uint8_t> text_frame(char start, const uint8_t* p, std::size_t n)
{
    std::vector<uint8_t> f;
    f.push_back(static_cast<uint8_t>(start));
    f.insert(f.end(), p, p + n);
    char digits[16];
    if (start == '$') std::snprintf(digits, sizeof digits, "*%02X\r\n", ugv::novatel::nmea_checksum(p, n));
    else std::snprintf(digits, sizeof digits, "*%08X\r\n", ugv::novatel::crc32(p, n));
    f.insert(f.end(), digits, digits + std::char_traits<char>::length(digits));
    return f;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    if (size == 0 || size > 9000) return 0;
    const uint8_t* p = data + 1;
    const std::size_t n = size - 1;
    std::vector<uint8_t> frame;
    switch (data[0] % 5) {
    case 0: frame = binary_frame(p, n, true); break;
    case 1: frame = binary_frame(p, n, false); break;
    case 2: frame = text_frame('#', p, n); break;
    case 3: frame = text_frame('%', p, n); break;
    default: frame = text_frame('$', p, n); break;
    }
    ugv::fuzz::ReceiverPath path;
    path.feed(frame.data(), frame.size(), 1'700'000'000'000'000);
    // A binary frame always frames (the target set its lengths); so must it come out.
    if (data[0] % 5 < 2 && path.decoder().splitter_counters().frames_total() != 1) std::abort();
    return 0;
}
