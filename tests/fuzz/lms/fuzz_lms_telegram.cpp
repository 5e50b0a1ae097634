// A telegram body (CMD, DATA, STATUS) of any content, framed with a valid CRC so that it gets
// past the decoder into the scan and reply decoders (random bytes almost never carry a right
// CRC-16). The decoder must deliver exactly that telegram, and it must satisfy
// check_telegram.
#include <cstdlib>
#include <span>

#include "scan_invariants.hpp"
#include "ugv/sick_lms2xx/decoder.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    using namespace ugv::sick_lms2xx;
    // CMD + DATA + STATUS must fit LEN <= kMaxLen.
    if (size < 2 || size > kMaxLen) return 0;
    const uint8_t status = data[size - 1];
    const auto frame = encode_reply(data[0], std::span<const uint8_t>(data + 1, size - 2), status);

    Decoder decoder(kDeviceAddress);
    int telegrams = 0;
    decoder.feed(frame.data(), frame.size(), [&](const DecoderEvent& e) {
        if (e.kind != DecoderEvent::Kind::telegram) return;
        ++telegrams;
        if (e.telegram.command != data[0] || e.telegram.status != status || e.telegram.data.size() != size - 2) std::abort();
        ugv::fuzz::check_telegram(e.telegram);
    });
    if (telegrams != 1) std::abort();
    return 0;
}
