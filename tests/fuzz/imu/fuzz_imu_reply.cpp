// One GX1 reply with any data words behind a valid checksum: byte 0 picks the command (one
// of the protocol's, so the words reach its scaling), the rest are the words. The parser
// must return exactly that frame, and it must pass SamplePath's checks.
#include <cstdlib>
#include <vector>

#include "sample_path.hpp"
#include "ugv/microstrain_gx1/protocol.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    using namespace ugv::microstrain_gx1;
    if (size == 0) return 0;
    // The commands that have a reply, in byte order.
    std::vector<uint8_t> commands;
    for (int b = 0; b < 256; ++b) {
        if (is_command(static_cast<uint8_t>(b))) commands.push_back(static_cast<uint8_t>(b));
    }
    const uint8_t command = commands[data[0] % commands.size()];
    std::vector<uint16_t> words(reply_words(command), 0);
    for (std::size_t i = 0; i < words.size() && 2 + 2 * i < size; ++i) {
        words[i] = static_cast<uint16_t>(data[1 + 2 * i] << 8 | data[2 + 2 * i]);
    }
    const auto reply = encode_reply(command, words);
    FrameParser parser;
    parser.feed(reply.data(), reply.size(), 1'700'000'000'000'000);
    Frame f;
    if (!parser.next(f) || f.command != command || f.nwords != words.size()) std::abort();
    for (std::size_t i = 0; i < words.size(); ++i) {
        if (f.words[i] != words[i]) std::abort();
    }
    ugv::fuzz::SamplePath path;
    path.on_frame(f);
    return 0;
}
