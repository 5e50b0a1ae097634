// The slcan decoder fed any bytes in any split: never crashes, and every frame it reports
// encodes back to a valid line that decodes to the same frame.
#include <cstdlib>

#include "ugv/io/slcan_codec.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    ugv::io::slcan::Decoder d;
    const size_t split = size ? data[0] % (size + 1) : 0;
    auto events = d.feed(data, split);
    auto rest = d.feed(data + split, size - split);
    events.insert(events.end(), rest.begin(), rest.end());
    for (const auto& e : events) {
        if (e.kind != ugv::io::slcan::Event::Kind::frame) continue;
        const std::string line = ugv::io::slcan::encode_frame(e.frame);
        const auto again = ugv::io::slcan::decode_line(std::string_view(line).substr(0, line.size() - 1));
        if (again.kind != ugv::io::slcan::Event::Kind::frame || !(again.frame == e.frame)) std::abort();
    }
    return 0;
}
