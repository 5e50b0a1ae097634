// A ugv::io::ByteStream wired to a GpsEmulator in memory, on the real clock: the session
// talks to the emulator exactly as over a serial line, including a baud mismatch (the
// emulator then ignores what it receives and the host reads noise).
#pragma once

#include <chrono>
#include <deque>
#include <random>
#include <string>
#include <thread>

#include "gps_emulator.hpp"
#include "ugv/io/byte_stream.hpp"
#include "ugv/io/clock.hpp"

namespace ugv::novatel::test {

class EmulatorStream final : public io::ByteStream
{
public:
    EmulatorStream(sim::gps::GpsEmulator& emulator, int baud) : emulator_(emulator), baud_(baud) {}

    io::ReadResult read(uint8_t* buf, std::size_t cap, int timeout_ms) override
    {
        if (closed_) {
            return {io::ReadResult::Status::closed, 0, io::now_utime()};
        }
        const int64_t deadline = io::monotonic_us() + int64_t{timeout_ms} * 1000;
        for (;;) {
            pull();
            if (!pending_.empty()) {
                std::size_t n = 0;
                while (n < cap && !pending_.empty()) {
                    buf[n++] = static_cast<uint8_t>(pending_.front());
                    pending_.pop_front();
                }
                return {io::ReadResult::Status::data, n, io::now_utime()};
            }
            if (io::monotonic_us() >= deadline) {
                return {io::ReadResult::Status::timeout, 0, io::now_utime()};
            }
            std::this_thread::sleep_for(std::chrono::milliseconds(2));
        }
    }
    bool write(const uint8_t* data, std::size_t n) override
    {
        if (closed_) {
            return false;
        }
        if (baud_ == emulator_.baud()) {
            push(emulator_.on_host_bytes(data, n), true);
        }
        return true;
    }
    bool set_baud(int baud) override
    {
        baud_ = baud;
        return true;
    }
    int baud() const override { return baud_; }
    void flush_input() override { pending_.clear(); }
    const std::string& last_error() const override { return error_; }
    void close() { closed_ = true; }

private:
    void pull() { push(emulator_.tick(io::now_utime()), false); }
    void push(const std::string& bytes, bool reply)
    {
        // A reply to COM leaves at the old rate: it was produced before the switch.
        const bool matches = reply || baud_ == emulator_.baud();
        for (const char c : bytes) {
            pending_.push_back(matches ? c : static_cast<char>(rng_() & 0xFFU));
        }
    }

    sim::gps::GpsEmulator& emulator_;
    int baud_;
    bool closed_ = false;
    std::deque<char> pending_;
    std::mt19937 rng_{7};
    std::string error_;
};

}  // namespace ugv::novatel::test
