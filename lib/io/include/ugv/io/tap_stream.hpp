// A ByteStream that passes everything through to another one and shows each chunk read or
// written to a callback: how a daemon publishes the raw wire bytes (publish_raw).
#pragma once

#include <functional>

#include "ugv/io/byte_stream.hpp"

namespace ugv::io {

class TapStream final : public ByteStream
{
public:
    // to_device: false for bytes read from the device, true for bytes written to it.
    using Tap = std::function<void(bool to_device, const uint8_t* data, std::size_t n, int64_t utime)>;

    TapStream(ByteStream& inner, Tap tap) : inner_(inner), tap_(std::move(tap)) {}

    ReadResult read(uint8_t* buf, std::size_t cap, int timeout_ms) override
    {
        const ReadResult r = inner_.read(buf, cap, timeout_ms);
        if (tap_ && r.status == ReadResult::Status::data) tap_(false, buf, r.n, r.utime);
        return r;
    }
    bool write(const uint8_t* data, std::size_t n) override
    {
        const bool ok = inner_.write(data, n);
        if (tap_ && ok) tap_(true, data, n, 0);
        return ok;
    }
    bool set_baud(int baud) override { return inner_.set_baud(baud); }
    int baud() const override { return inner_.baud(); }
    void flush_input() override { inner_.flush_input(); }
    void drain_output() override { inner_.drain_output(); }
    const std::string& last_error() const override { return inner_.last_error(); }

private:
    ByteStream& inner_;
    Tap tap_;
};

}  // namespace ugv::io
