// The receiver path of ugv-gps without the port and the bus: Decoder (splitter + log
// decoders) then Interpreter, with the checks both GPS fuzz targets make on what comes out.
#pragma once

#include <cstddef>
#include <cstdint>

#include "ugv/novatel/decoder.hpp"
#include "ugv/novatel/interpreter.hpp"

namespace ugv::fuzz {

class ReceiverPath
{
public:
    // Feeds one chunk that arrived at chunk_utime; checks every message, fix and velocity.
    void feed(const uint8_t* data, std::size_t n, int64_t chunk_utime);
    uint64_t messages() const { return messages_; }
    const novatel::Decoder& decoder() const { return decoder_; }

private:
    void on_message(const novatel::Decoded& m, int64_t chunk_utime);

    novatel::Decoder decoder_;
    novatel::Interpreter interpreter_{novatel::InterpreterConfig{18, 20'000, 115200, 2'000'000}};
    uint64_t fed_ = 0;
    uint64_t messages_ = 0;
};

}  // namespace ugv::fuzz
